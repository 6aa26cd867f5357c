#pragma once
// Candidates of the candidate stream (core/candidate_stream.h), drawn kLanes at a time in vector
// registers: Philox, the uniforms and Heitz's map are the same arithmetic as the scalar
// lightsampler::philox4x32, uniform_float and triangle_map, lane by lane, so every candidate is
// bit for bit the one the GPU draws.

#include <atomic>
#include <cstdint>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/candidate_stream.h"
#include "core/density.h"
#include "core/geometry.h"
#include "cpu/passes.h"
#include "lightsampler/random.h"
#include "lightsampler/sample.h"

namespace lightsampler::cpu {

inline constexpr int kLanes = 16;
static_assert(kLanes <= 32, "a mask of accepted candidates is 32 bits");

/// Candidates first .. first + kLanes - 1 of one segment. Philox output words 0 and 1 give the
/// barycentrics, word 2 the uniform that decides acceptance, word 3 (as a double in [0, 1)) the
/// position in the area CDF where plain rejection sampling picks the triangle.
struct CandidateBatch {
  alignas(64) float b1[kLanes];
  alignas(64) float b2[kLanes];
  alignas(64) float accept[kLanes];
  alignas(64) double pick[kLanes];
};

void draw_candidates(std::uint32_t triangle, std::uint64_t segment, std::uint64_t first, PhiloxKey key,
                     CandidateBatch& out);

/// TRS's test of a batch on triangle t, in vector registers: bit l set when accept[l] * bound <
/// the density at the lane's point, bit for bit the scalar
/// `accept * bound < core::texel_triangle_density(t, ...)`.
std::uint32_t accepted_on_triangle(const core::TexelTriangle& t, const core::DensityMap& map, float bound,
                                   const CandidateBatch& batch);

/// Candidates and samples of a walk, summed over segments.
struct WalkTally {
  std::uint64_t candidates = 0;
  std::uint64_t exhausted = 0;
  std::uint64_t exact = 0;  ///< slots drawn exactly after the limit stopped a walk
};

/// Fills the slots of one segment, out[0 .. run.slots), from its candidate stream:
/// judge(first) draws candidates first .. first + kLanes - 1 and returns a mask of the accepted
/// ones (bit l for candidate first + l); lane_sample(l) is then candidate first + l as a sample.
/// All kLanes are judged before any fills a slot, so that their texel reads overlap; those after
/// the last slot is filled are not counted. Returns the slots filled: fewer than run.slots when
/// the limit stopped the walk.
template <class Judge, class LaneSample>
std::uint64_t walk_segment(const core::SegmentRun& run, core::TryLimit limit, Sample* out, Judge&& judge,
                           LaneSample&& lane_sample, WalkTally& tally) {
  core::SegmentFill fill(run.slots, limit);
  for (std::uint64_t first = 0; !fill.done(); first += kLanes) {
    const std::uint32_t accepted = judge(first);
    if (fill.open(kLanes)) {
      // Without branches on the accepted bits, which are random: every lane writes, and the
      // next one overwrites a rejected lane's sample.
      Sample* slot = out + fill.filled();
      for (int l = 0; l < kLanes; ++l) {
        *slot = lane_sample(l);
        slot += (accepted >> l) & 1u;
      }
      fill.take_open(accepted, kLanes);
    } else {
      fill.take(accepted, kLanes, [&](int l, std::uint64_t slot) { out[slot] = lane_sample(l); });
    }
  }
  tally.candidates += fill.tries();
  tally.exhausted += fill.exhausted();
  return fill.filled();
}

/// Walks the output, whose element e holds the slots cdf[e - 1] .. cdf[e] - 1 (inclusive CDF),
/// in tasks of `grain` slots: `walk(run, tally)` fills the slots of one segment run (walk_segment).
template <class Walk>
RealizationResult walk_output(std::span<const std::uint64_t> cdf, std::uint64_t grain, const Walk& walk) {
  const std::uint64_t n = cdf.empty() ? 0 : cdf.back();
  std::atomic<std::uint64_t> candidates{0}, exhausted{0}, exact{0};
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, n, grain), [&](const tbb::blocked_range<std::uint64_t>& r) {
    WalkTally tally;
    core::for_each_segment(cdf, r.begin(), r.end(), [&](const core::SegmentRun& run) { walk(run, tally); });
    candidates.fetch_add(tally.candidates, std::memory_order_relaxed);
    exhausted.fetch_add(tally.exhausted, std::memory_order_relaxed);
    exact.fetch_add(tally.exact, std::memory_order_relaxed);
  });
  return {candidates.load(), exhausted.load(), exact.load()};
}

}  // namespace lightsampler::cpu
