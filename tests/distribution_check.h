#pragma once
// Chi-square tests of a sample set against the density, with expected counts per (triangle,
// texel) cell computed independently of the sampler (polygon clipping). Shared by the CPU and
// Vulkan distribution tests.
//
// TRS: conditional on each triangle's count N_T (set by stochastic rounding, tested in
// rounding_test), the N_T samples of a triangle are i.i.d. with probability proportional to
// D(texel) Area(texel n T): one table per triangle, the statistics summed.
// Rejection sampling: the N samples are i.i.d. over all cells: one multinomial table.

#include <span>
#include <vector>

#include "core/geometry.h"
#include "lightsampler/sampler.h"
#include "sampler_fixtures.h"
#include "support/chi_square.h"

namespace trs_test {

/// Significance of each test: family alpha 0.01 with the Sidak correction over the 22 tests that
/// expect to pass: CPU TRS and rejection sampling, Vulkan TRS (raster and compute counting) and
/// rejection sampling, and refined TRS on the CPU and on Vulkan, over 3 scenarios; and the
/// correctly mapped half of the refinement's rejection test.
inline const double kDistributionAlpha = sidak_alpha(0.01, 22);

struct Scenario {
  const char* name;
  Mesh mesh;
  Map map;
  double target;
  std::uint64_t seed;
};

/// Random triangles over a sparse map with wrap and with clamp beyond [0, 1], and two large
/// triangles over a fine sparse map.
std::vector<Scenario> scenarios();

/// The scenario's triangles in texel space, as the samplers build them.
std::vector<lightsampler::core::TexelTriangle> texel_triangles(const Scenario& s);

ChiSquareResult test_per_triangle(const Scenario& s, std::span<const lightsampler::Sample> samples);
ChiSquareResult test_all_cells(const Scenario& s, std::span<const lightsampler::Sample> samples);

}  // namespace trs_test
