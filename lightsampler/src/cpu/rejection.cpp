#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>

#include "cpu/passes.h"
#include "lightsampler/triangle_map.h"

namespace lightsampler::cpu {

float rejection_distribution(std::span<const core::TriangleRecord> triangles,
                             std::span<const core::DensityMap> maps, Buffer<double>& area_cdf) {
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
                                   float global_max_density, std::uint64_t sample_count,
                                   PhiloxKey key, std::uint32_t max_tries, Buffer<Sample>& samples) {
  samples.resize(sample_count);
  if (sample_count == 0) return {0, 0};
  const double total_area = area_cdf.back();
  const std::size_t last = area_cdf.size() - 1;
  std::atomic<std::uint64_t> candidates{0}, exhausted{0};
  tbb::parallel_for(
      // Small blocks: a sample may try hundreds of candidates, and small counts must still
      // spread over every thread.
      tbb::blocked_range<std::uint64_t>(0, sample_count, 1 << 10),
      [&](const tbb::blocked_range<std::uint64_t>& r) {
        std::uint64_t tries = 0, gave_up = 0;
        for (std::uint64_t i = r.begin(); i != r.end(); ++i) {
          for (std::uint32_t attempt = 0;;) {
            const PhiloxCounter u =
                philox4x32({std::uint32_t(i), std::uint32_t(i >> 32), attempt, 0}, key);
            const double pick = uniform_double(u[0]) * total_area;
            const auto tri = std::uint32_t(std::min<std::size_t>(
                std::upper_bound(area_cdf.begin(), area_cdf.end(), pick) - area_cdf.begin(), last));
            const Barycentrics b = triangle_map(uniform_float(u[1]), uniform_float(u[2]));
            const float d = core::texel_triangle_density(triangles[tri], maps, b.b1, b.b2);
            ++attempt;
            const bool accepted = uniform_float(u[3]) * global_max_density < d;
            if (accepted || attempt == max_tries) {
              samples[i] = {tri, b.b1, b.b2};
              gave_up += accepted ? 0 : 1;
              tries += attempt;
              break;
            }
          }
        }
        candidates.fetch_add(tries, std::memory_order_relaxed);
        exhausted.fetch_add(gave_up, std::memory_order_relaxed);
      });
  return {candidates.load(), exhausted.load()};
}

}  // namespace lightsampler::cpu
