#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>

#include "core/area_pick.h"
#include "cpu/cdf_rejection.h"

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
  return cdf_rejection_sample(area_cdf, area_guide, sample_count, key, max_tries, samples,
                              [&](std::uint32_t tri, float b1, float b2, float accept, Sample& out) {
                                out = {tri, b1, b2};
                                return accept * global_max_density < core::texel_triangle_density(triangles[tri], maps, b1, b2);
                              });
}

}  // namespace lightsampler::cpu
