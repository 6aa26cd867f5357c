#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>

#include "core/area_pick.h"
#include "cpu/passes.h"
#include "cpu/candidates.h"

namespace lightsampler::cpu {

float rejection_distribution(std::span<const core::TriangleRecord> triangles,
                             std::span<const core::DensityMap> maps, Buffer<double>& area_cdf,
                             std::vector<std::uint32_t>& area_guide) {
  const std::size_t n = triangles.size();
  area_cdf.resize(n);
  tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, n, 1 << 14), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double sum, bool is_final) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          sum += triangles[i].area;
          if (is_final) area_cdf[i] = sum;
        }
        return sum;
      },
      std::plus<>());
  area_guide = core::area_guide(area_cdf.span());
  // D_M^max: the largest texel of any map, scaled. Maps change every frame, so it is recomputed.
  float bound = 0;
  for (const core::DensityMap& map : maps) {
    const float m = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, map.texels.size(), 1 << 16), 0.0f,
        [&](const tbb::blocked_range<std::size_t>& r, float acc) {
          for (std::size_t i = r.begin(); i != r.end(); ++i) acc = std::max(acc, map.texels[i]);
          return acc;
        },
        [](float a, float b) { return std::max(a, b); });
    bound = std::max(bound, m * map.scale);
  }
  return bound;
}

RealizationResult rejection_sample(std::span<const core::TexelTriangle> triangles,
                                   std::span<const core::DensityMap> maps, std::span<const double> area_cdf,
                                   std::span<const std::uint32_t> area_guide, float global_max_density, std::uint64_t sample_count,
                                   PhiloxKey key, std::uint32_t max_tries, Buffer<Sample>& samples) {
  samples.resize(sample_count);
  if (sample_count == 0) return {0, 0};
  // The whole output is one run of segments, as if one triangle held every sample.
  const std::uint64_t output[1] = {sample_count};
  std::atomic<std::uint64_t> candidates{0}, exhausted{0};
  tbb::parallel_for(
      // Small blocks: a sample may try hundreds of candidates, and small counts must still
      // spread over every thread.
      tbb::blocked_range<std::uint64_t>(0, sample_count, 1 << 10),
      [&](const tbb::blocked_range<std::uint64_t>& r) {
        WalkTally tally;
        core::for_each_segment(output, r.begin(), r.end(), [&](const core::SegmentRun& run) {
          CandidateBatch batch;
          auto draw = [&](std::uint64_t first, Sample(&out)[kLanes]) {
            std::uint32_t accepted = 0;
            draw_candidates(0, run.segment, first, key, batch);
            for (int l = 0; l < kLanes; ++l) {
              const std::uint32_t tri = core::pick_by_area(area_cdf, area_guide, batch.pick[l]);
              const float d = core::texel_triangle_density(triangles[tri], maps, batch.b1[l], batch.b2[l]);
              accepted |= std::uint32_t(batch.accept[l] * global_max_density < d) << l;
              out[l] = {tri, batch.b1[l], batch.b2[l]};
            }
            return accepted;
          };
          walk_segment(run, max_tries, samples.data() + run.first, draw, tally);
        });
        candidates.fetch_add(tally.candidates, std::memory_order_relaxed);
        exhausted.fetch_add(tally.exhausted, std::memory_order_relaxed);
      });
  return {candidates.load(), exhausted.load()};
}

}  // namespace lightsampler::cpu
