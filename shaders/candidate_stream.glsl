// The candidate stream (lightsampler/src/core/candidate_stream.h), walked by a subgroup: the
// lanes draw consecutive candidates of one segment together, and prefix counts over the lanes
// assign the slots, so no lane waits for another's rejection loop.
//
// The including shader defines, before including this file:
//   bool draw_candidate(uint64_t segment, uint64_t candidate, out Sample drawn)
// which returns whether candidate `candidate` of segment `segment` is accepted.
#ifndef LIGHTSAMPLER_CANDIDATE_STREAM_GLSL
#define LIGHTSAMPLER_CANDIDATE_STREAM_GLSL

#include "workgroup.glsl"

// Fills `slots` slots of segment `segment`, samples `first` on of the buffer at `samples`. Call with the whole subgroup,
// every argument subgroup-uniform (the loop's trip count is). Each lane draws candidate
// j + lane; a candidate fills a slot when accepted, or when it is the max_tries-th rejection in
// a row (counted across rounds by `rejections`) and the limit does not `stop`, as
// core::SegmentFill::take. Returns the slots filled: fewer than `slots` when the limit stopped
// the walk (subgroup-uniform).
uint walk_segment(uint64_t samples, uint64_t segment, uint64_t first, uint slots, uint max_tries, bool stop,
                  inout WalkTally tally) {
  // Lanes numbered among the active ones, in invocation order (the order of the scans below).
  uint lane = subgroupExclusiveAdd(1u);
  uint width = subgroupAdd(1u);
  uint filled = 0u;
  uint64_t rejections = 0ul;  // rejections in a row before this round, modulo max_tries
  for (uint64_t j = 0ul; filled < slots; j += uint64_t(width)) {
    Sample candidate;
    bool accepted = draw_candidate(segment, j + uint64_t(lane), candidate);
    // Rejections in a row up to and including this lane: since the last accepted lane, or
    // since the round began plus those carried in.
    int last_accepted = subgroupInclusiveMax(accepted ? int(lane) : -1);
    uint64_t run = last_accepted >= 0 ? uint64_t(lane - uint(last_accepted))
                                      : rejections + uint64_t(lane) + 1ul;
    // The first lane at the limit stops the walk, if the limit stops; the lanes after it do not count.
    uint stop_lane = stop ? subgroupMin(run >= uint64_t(max_tries) ? lane : width) : width;
    bool fills = lane < stop_lane && (accepted || (!stop && run % uint64_t(max_tries) == 0ul));
    uint before = subgroupExclusiveAdd(fills ? 1u : 0u);
    bool drawn = before < slots - filled && lane <= stop_lane;  // the segment was not yet full nor stopped
    if (fills && drawn) Samples(samples + (first + uint64_t(filled + before)) * uint64_t(kSampleBytes)).v[0] = candidate;
    tally.candidates += drawn ? 1ul : 0ul;
    tally.exhausted += fills && drawn && !accepted ? 1ul : 0ul;
    filled += min(subgroupAdd(fills ? 1u : 0u), slots - filled);
    if (stop_lane < width) break;
    rejections = subgroupMax(lane == width - 1u ? run % uint64_t(max_tries) : 0ul);
  }
  return filled;
}

// The whole output as one run of segments, as if one element held every sample (plain rejection
// sampling, FRS): the subgroups take its segments in turn, and the frame's totals count their
// tries. Call at the top level of main.
void walk_output(Totals totals, uint64_t samples, uint max_tries) {
  uint64_t n = totals.t.realized;
  uint64_t segments = (n + uint64_t(kSegmentSlots) - 1ul) / uint64_t(kSegmentSlots);
  uint64_t stride = uint64_t(gl_NumWorkGroups.x) * uint64_t(gl_NumSubgroups);
  WalkTally tally = WalkTally(0ul, 0ul, 0ul);
  for (uint64_t s = uint64_t(gl_WorkGroupID.x) * uint64_t(gl_NumSubgroups) + uint64_t(gl_SubgroupID); s < segments;
       s += stride) {
    uint64_t first = s * uint64_t(kSegmentSlots);
    walk_segment(samples, s, first, uint(min(uint64_t(kSegmentSlots), n - first)), max_tries, false, tally);
  }
  count_tries(totals, tally);
}

#endif
