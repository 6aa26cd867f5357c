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

/// The chi-square checks of the sample distribution that expect to pass, across the test
/// executables: each runs once per scenario unless `per_scenario` is false. A check that uses
/// kDistributionAlpha belongs here, so that the family's size follows the list.
struct FamilyMember {
  const char* check;
  bool per_scenario;
};
inline constexpr FamilyMember kDistributionFamily[] = {
    {"CPU TRS (distribution_test)", true},
    {"CPU TRS with exact draws after one rejection (distribution_test)", true},
    {"CPU TRS on a sliver of density, 1e-2 of the triangle (sliver_test)", false},
    {"CPU TRS on a sliver of density, 1e-4 of the triangle (sliver_test)", false},
    {"CPU TRS on a sliver of density, 1e-6 of the triangle (sliver_test)", false},
    {"CPU rejection sampling (distribution_test)", true},
    {"CPU naive stratification (distribution_test)", true},
    {"CPU fast rejection sampling (distribution_test)", true},
    {"CPU TRS over all cells, beside Eq. 6's overlaps (distribution_test)", false},
    {"CPU refined TRS (refinement_test)", true},
    {"refinement: the correctly mapped samples (refinement_test)", false},
    {"Vulkan TRS, compute counting (vulkan_sampler_test)", true},
    {"Vulkan TRS, raster counting (vulkan_sampler_test)", true},
    {"Vulkan rejection sampling (vulkan_sampler_test)", true},
    {"Vulkan refined TRS (vulkan_sampler_test)", true},
    {"Vulkan naive stratification (vulkan_sampler_test)", true},
    {"Vulkan fast rejection sampling (vulkan_sampler_test)", true},
};

/// How many tests the family holds: its members times the scenarios they run over.
std::size_t distribution_family_size();

/// Significance of each test: family alpha 0.01 with the Sidak correction over the family.
inline const double kDistributionAlpha = sidak_alpha(0.01, distribution_family_size());

/// The scenario's triangles in texel space, as the samplers build them.
std::vector<lightsampler::core::TexelTriangle> texel_triangles(const Scenario& s);

ChiSquareResult test_per_triangle(const Scenario& s, std::span<const lightsampler::Sample> samples);
ChiSquareResult test_all_cells(const Scenario& s, std::span<const lightsampler::Sample> samples);

}  // namespace trs_test
