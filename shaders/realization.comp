#version 460
#extension GL_GOOGLE_include_directive : require
// Realization (Algorithm 4) through the candidate stream: each subgroup takes chunks of
// kSegmentSlots samples in turn and walks every segment that starts in its chunk (at most one
// per triangle: core::for_each_segment), so small triangles share a subgroup and large ones
// spread over many. Candidates from Heitz's map, accepted against D_T^max; a walk that stops
// after exact_after rejections in a row lists its segment, and the exact pass
// (realization_exact.comp) draws the rest of it from the triangle's texel pieces. Exact draws
// live in a pass of their own so that their code costs this one nothing (registers, and
// llvmpipe runs the pass 13 times slower with it inside). The same samples as the CPU backend's.
#include "workgroup.glsl"
#include "inverse_cdf.glsl"
#include "texel_pieces.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizationPush p; };

// The triangle whose segment is being walked.
uint walked_triangle;
TexelTriangle walked_texels;
DensityMap walked_map;
float walked_bound;

bool draw_candidate(uint64_t segment, uint64_t candidate, out Sample drawn) {
  uvec4 u = philox4x32(candidate_counter(walked_triangle, segment, candidate), uvec2(p.key0, p.key1));
  vec2 b = triangle_map(uniform_float(u.x), uniform_float(u.y));
  vec2 point = texel_space_point(walked_texels, b);
  drawn = Sample(walked_triangle, b.x, b.y);
  return uniform_float(u.z) * walked_bound < point_density(walked_map, p.texels, point.x, point.y);
}

#include "candidate_stream.glsl"

// Lists a stopped walk for the exact pass: one record per segment, by one lane.
void list_stopped(uint position, uint64_t segment, uint filled) {
  if (!subgroupElect()) return;
  Uints list = Uints(p.stopped);
  uint r = atomicAdd(list.v[0], 1u);
  if (r >= list.v[1]) return;  // beyond the capacity, which holds every segment of a frame
  uint at = kStoppedHeaderUints + r * kStoppedRecordUints;
  uvec2 words = unpackUint2x32(segment);
  list.v[at] = position;
  list.v[at + 1u] = filled;
  list.v[at + 2u] = words.x;
  list.v[at + 3u] = words.y;
  atomicMax(list.v[kStoppedDispatch], min(r / gl_NumSubgroups + 1u, kExactWorkgroups));
}

// The processing index of the triangle holding sample `sample_index`, searched within the guide
// table's bounds when the frame has one.
uint first_position(uint64_t sample_index) {
  if (p.guide == 0ul) return processing_index(p.cdf, p.triangle_count, sample_index);
  uint b = uint(sample_index / guide_bucket(Totals(p.totals).t.sample_count, p.triangle_count));
  return first_above(p.cdf, sample_index, Uints(p.guide).v[b], Uints(p.guide).v[b + 1u]);
}

// The next processing index after `position` with slots below `hi`, or triangle_count: a binary
// search past the triangles without slots (most of them when triangles outnumber samples), so
// a chunk's walk takes at most kSegmentSlots steps.
uint next_position(uint position, uint64_t hi) {
  uint64_t end = cdf_at(p.cdf, position);
  if (end >= hi || position + 1u >= p.triangle_count) return p.triangle_count;
  return first_above(p.cdf, end, position + 1u, p.triangle_count - 1u);
}

void main() {
  Totals totals = Totals(p.totals);
  uint64_t n = totals.t.realized;
  uint64_t chunks = (n + uint64_t(kSegmentSlots) - 1ul) / uint64_t(kSegmentSlots);
  uint64_t stride = uint64_t(gl_NumWorkGroups.x) * uint64_t(gl_NumSubgroups);
  WalkTally tally = WalkTally(0ul, 0ul, 0ul);
  // Every bound below is subgroup-uniform: the subgroup walks together.
  for (uint64_t c = uint64_t(gl_WorkGroupID.x) * uint64_t(gl_NumSubgroups) + uint64_t(gl_SubgroupID); c < chunks;
       c += stride) {
    uint64_t lo = c * uint64_t(kSegmentSlots), hi = min(lo + uint64_t(kSegmentSlots), n);
    for (uint position = first_position(lo); position < p.triangle_count; position = next_position(position, hi)) {
      uint64_t start = position > 0u ? cdf_at(p.cdf, position - 1u) : 0ul, end = cdf_at(p.cdf, position);
      if (start >= hi) break;
      uint64_t segment = start >= lo ? 0ul : (lo - start + uint64_t(kSegmentSlots) - 1ul) / uint64_t(kSegmentSlots);
      uint64_t first = start + segment * uint64_t(kSegmentSlots);
      if (first >= min(hi, end)) continue;
      // N_T > 0, so the triangle has a map and a positive bound.
      walked_triangle = Uints(p.inverse).v[position];
      walked_texels = Triangles(p.triangles).v[walked_triangle];
      walked_map = Maps(p.maps).v[walked_texels.map];
      walked_bound = uintBitsToFloat(Uints(p.max_density).v[walked_triangle]);
      uint slots = uint(min(uint64_t(kSegmentSlots), end - first));
      // The rejection loop's limit (core::TrsTries::rejection), where the device draws exactly.
      PieceLattice l = piece_lattice(walked_texels);
      bool stop = p.exact_after > 0u && lattice_columns(l) * uint64_t(l.y1 - l.y0 + 1l) <= uint64_t(p.exact_cells);
      uint limit = stop ? min(p.max_tries, p.exact_after) : p.max_tries;
      uint filled = walk_segment(p.samples, segment, first, slots, limit, stop, tally);
      if (filled < slots) list_stopped(position, segment, filled);
    }
  }
  count_tries(totals, tally);
}
