#pragma once
// Rejection sampling over a CDF of elements (triangles, or FRS's micro-triangles): an element by
// the CDF, a uniform point on it, accepted against a bound, through the candidate stream over
// the whole output (core/candidate_stream.h), so that the samples depend on the seed alone.

#include <cstdint>
#include <span>

#include "core/area_pick.h"
#include "cpu/candidates.h"
#include "cpu/passes.h"

namespace lightsampler::cpu {

/// `sample_count` samples; `judge(element, b1, b2, accept, sample)` turns a candidate (a uniform
/// point of an element, and a uniform in [0, 1) for its acceptance) into a sample and says
/// whether it is accepted. `cdf` is inclusive, `guide` its cutpoints (core/area_pick.h).
template <class Judge>
RealizationResult cdf_rejection_sample(std::span<const double> cdf, std::span<const std::uint32_t> guide,
                                       std::uint64_t sample_count, PhiloxKey key, std::uint32_t max_tries,
                                       Buffer<Sample>& samples, const Judge& judge) {
  samples.resize(sample_count);
  if (sample_count == 0) return {};
  // The whole output is one run of segments, as if one element held every sample. Small tasks:
  // a sample may try hundreds of candidates, and small counts must still spread over every thread.
  const std::uint64_t output[1] = {sample_count};
  return walk_output(output, 1 << 10, [&](const core::SegmentRun& run, WalkTally& tally) {
    CandidateBatch batch;
    Sample lanes[kLanes];
    auto judge_lanes = [&](std::uint64_t first) {
      std::uint32_t accepted = 0;
      draw_candidates(0, run.segment, first, key, batch);
      for (int l = 0; l < kLanes; ++l) {
        const std::uint32_t element = core::pick_by_area(cdf, guide, batch.pick[l]);
        accepted |= std::uint32_t(judge(element, batch.b1[l], batch.b2[l], batch.accept[l], lanes[l])) << l;
      }
      return accepted;
    };
    walk_segment(run, {max_tries}, samples.data() + run.first, judge_lanes, [&](int l) { return lanes[l]; }, tally);
  });
}

}  // namespace lightsampler::cpu
