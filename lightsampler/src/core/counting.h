#pragma once
// The counting pass (Algorithm 2, lines 1-8; Eq. 1-2) on the host: the exact integral of the
// density over each triangle. The CPU backend's counting pass, and what the adaptive subdivision
// measures its triangles with.

#include <cstdint>
#include <span>

#include "core/density.h"
#include "core/geometry.h"
#include "lightsampler/buffer.h"
#include "lightsampler/sampler.h"

namespace lightsampler::core {

/// Per triangle, the exact integral of the density N-bar_T (texel overlaps by the closed form of
/// Section 4, or by the alternative `overlap` names) and the max density D_T^max over the texels
/// it overlaps. Returns N-bar.
double count(std::span<const TriangleRecord> triangles, std::span<const TexelTriangle> texel_triangles,
             std::span<const DensityMap> maps, Buffer<double>& expected_counts, Buffer<float>& max_density,
             Overlap overlap = Overlap::closed_form);

/// As count(), for the triangles whose map is marked in `stale` (indexed by map) only; the others
/// keep their values. The same integrals and the same sum: the same results as count().
double recount(std::span<const TriangleRecord> triangles, std::span<const TexelTriangle> texel_triangles,
               std::span<const DensityMap> maps, std::span<const std::uint8_t> stale,
               Buffer<double>& expected_counts, Buffer<float>& max_density,
               Overlap overlap = Overlap::closed_form);

/// Sum in a fixed order, whatever the thread count: totals must be reproducible.
double sum(std::span<const double> values);

/// Integral of the density over one triangle and its max density (the body of count()).
struct TriangleIntegral {
  double expected;  ///< N-bar_T
  float max_density;
};
TriangleIntegral integrate_triangle(const TriangleRecord& triangle, const TexelTriangle& texel,
                                    std::span<const DensityMap> maps, Overlap overlap = Overlap::closed_form);

}  // namespace lightsampler::core
