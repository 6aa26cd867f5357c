#include "cpu/frs.h"

#include "core/density.h"
#include "cpu/cdf_rejection.h"

namespace lightsampler::cpu {

RealizationResult frs_sample(const core::FrsTable& table, std::span<const core::TexelTriangle> triangles,
                             std::span<const core::DensityMap> maps, std::uint64_t sample_count,
                             PhiloxKey key, std::uint32_t max_tries, Buffer<Sample>& samples) {
  if (table.size() == 0) sample_count = 0;
  return cdf_rejection_sample(
      table.cdf.span(), table.guide, sample_count, key, max_tries, samples,
      [&](std::uint32_t m, float s1, float s2, float accept, Sample& out) {
        // The micro-triangle's point, in its parent's barycentrics.
        const auto& c = table.corners[m];
        const float b1 = c[0] + s1 * (c[2] - c[0]) + s2 * (c[4] - c[0]);
        const float b2 = c[1] + s1 * (c[3] - c[1]) + s2 * (c[5] - c[1]);
        const std::uint32_t tri = table.parent[m];
        out = {tri, b1, b2};
        if (!(b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f)) return false;
        return accept * table.bound[m] < core::texel_triangle_density(triangles[tri], maps, b1, b2);
      });
}

}  // namespace lightsampler::cpu
