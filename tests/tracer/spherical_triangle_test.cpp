// Spherical triangles (tracer/src/strategies/spherical_triangle.h): the solid angle a triangle
// subtends, and points drawn uniformly in it.
//
// Solid angle: against the integral of |cos theta_l| / d^2 over the triangle by the midpoint rule
// on 1000^2 sub-triangles, within 1e-4 relative, and against the exact value for a cube's face
// seen from its centre.
//
// Sampling. Hypothesis: the points' area density is |cos theta_l| / (d^2 omega), uniform in
// solid angle. Test: Pearson chi-square of 200,000 points (seed 1 per configuration) over the
// triangle cut into 16^2 sub-triangles, expected counts from that density integrated by the
// midpoint rule on 16^2 pieces of each cell and normalised to the sample count (so that the
// solid angle under test plays no part); family alpha 0.01 over the four configurations, Sidak.
// Uniform points by area must fail the same check where the triangle is near.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <lightsampler/random.h>

#include "strategies/spherical_triangle.h"
#include "support/chi_square.h"

namespace {

using tracer::sample_spherical_triangle;
using tracer::solid_angle;
using Triangle = std::array<glm::vec3, 3>;

struct Configuration {
  const char* name;
  Triangle v;
  glm::vec3 p;
};

const Triangle kTriangle = {glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.5f, 1.5f, 0.0f)};

/// From above the triangle's interior to far away; omega from about 4.5 sr down to 4e-4 sr.
const std::vector<Configuration> kConfigurations = {
    {"near, above its interior", kTriangle, {0.8f, 0.5f, 0.12f}},
    {"at a moderate distance", kTriangle, {0.3f, -0.4f, 1.5f}},
    {"at a grazing angle, from behind", kTriangle, {4.0f, 2.5f, -0.4f}},
    {"far", kTriangle, {-20.0f, 30.0f, 40.0f}},
};

glm::dvec3 point(const Triangle& v, double b1, double b2) {
  return (1.0 - b1 - b2) * glm::dvec3(v[0]) + b1 * glm::dvec3(v[1]) + b2 * glm::dvec3(v[2]);
}

/// |cos theta_l| / d^2 at barycentrics (b1, b2): the solid angle per unit area there.
double solid_angle_per_area(const Triangle& v, const glm::dvec3& p, double b1, double b2) {
  const glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(v[1] - v[0]), glm::dvec3(v[2] - v[0])));
  const glm::dvec3 d = point(v, b1, b2) - p;
  const double d2 = glm::dot(d, d);
  return std::abs(glm::dot(n, d)) / (d2 * std::sqrt(d2));
}

double area(const Triangle& v) { return 0.5 * glm::length(glm::cross(glm::dvec3(v[1] - v[0]), glm::dvec3(v[2] - v[0]))); }

/// Sub-triangle k of the triangle (b1, b2) in [0,1]^2, b1 + b2 <= 1, cut into n^2: corners of
/// upright cells (i, j), (i+1, j), (i, j+1) and of inverted ones (i+1, j), (i, j+1), (i+1, j+1),
/// over n. Cells are numbered 2 (i n + j) + (inverted ? 1 : 0); those past the diagonal are empty.
std::array<glm::dvec2, 3> cell_corners(int n, int cell) {
  const int i = cell / 2 / n, j = cell / 2 % n;
  const double s = 1.0 / n;
  if (cell % 2 == 0) return {glm::dvec2(i * s, j * s), glm::dvec2((i + 1) * s, j * s), glm::dvec2(i * s, (j + 1) * s)};
  return {glm::dvec2((i + 1) * s, j * s), glm::dvec2(i * s, (j + 1) * s), glm::dvec2((i + 1) * s, (j + 1) * s)};
}

bool cell_exists(int n, int cell) {
  const int i = cell / 2 / n, j = cell / 2 % n;
  return cell % 2 == 0 ? i + j <= n - 1 : i + j <= n - 2;
}

int cell_of(int n, float b1, float b2) {
  const double x = double(b1) * n, y = double(b2) * n;
  const int i = std::min(int(x), n - 1), j = std::min(int(y), n - 1);
  const bool upright = (x - i) + (y - j) < 1.0 || i + j == n - 1;
  return 2 * (i * n + j) + (upright ? 0 : 1);
}

/// The integral of |cos theta_l| / d^2 over the part of the triangle with barycentrics in the
/// sub-triangle `corners`, by the midpoint rule on m^2 pieces.
double integrate(const Triangle& v, const glm::dvec3& p, const std::array<glm::dvec2, 3>& corners, int m) {
  // The unit triangle of barycentrics has area 1/2: a sub-triangle's share is twice its area.
  const double piece_area = area(v) * std::abs((corners[1].x - corners[0].x) * (corners[2].y - corners[0].y) -
                                                     (corners[2].x - corners[0].x) * (corners[1].y - corners[0].y)) /
                            (double(m) * m);
  double sum = 0.0;
  for (int cell = 0; cell < 2 * m * m; ++cell) {
    if (!cell_exists(m, cell)) continue;
    const std::array<glm::dvec2, 3> c = cell_corners(m, cell);
    const glm::dvec2 local = (c[0] + c[1] + c[2]) / 3.0;
    const glm::dvec2 b = corners[0] + local.x * (corners[1] - corners[0]) + local.y * (corners[2] - corners[0]);
    sum += solid_angle_per_area(v, p, b.x, b.y);
  }
  return sum * piece_area;
}

TEST(SphericalTriangle, SolidAngleMatchesTheIntegralOverTheTriangle) {
  const std::array<glm::dvec2, 3> whole = {glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1)};
  for (const Configuration& c : kConfigurations) {
    const double expected = integrate(c.v, glm::dvec3(c.p), whole, 1000);
    EXPECT_NEAR(solid_angle(c.v, c.p), expected, 1e-4 * expected) << c.name;
  }
}

// A cube's face subtends a sixth of the sphere at its centre; each half of it by a diagonal, a
// twelfth.
TEST(SphericalTriangle, SolidAngleOfHalfACubeFace) {
  const Triangle half = {glm::vec3(-1, -1, 1), glm::vec3(1, -1, 1), glm::vec3(1, 1, 1)};
  EXPECT_NEAR(solid_angle(half, glm::vec3(0.0f)), 4.0 * std::numbers::pi / 12.0, 1e-12);
  EXPECT_EQ(solid_angle(half, glm::vec3(5.0f, 0.0f, 1.0f)), 0.0) << "seen edge-on";
}

constexpr int kCells = 16, kSamples = 200000;

/// Chi-square of `b` (barycentrics) against the density |cos theta_l| / d^2, normalised.
trs_test::ChiSquareResult test_density(const Configuration& c, const std::vector<lightsampler::Barycentrics>& b) {
  std::vector<double> observed(2 * kCells * kCells, 0.0), expected(observed.size(), 0.0);
  for (const lightsampler::Barycentrics& s : b) observed[cell_of(kCells, s.b1, s.b2)] += 1.0;
  double total = 0.0;
  for (int cell = 0; cell < int(expected.size()); ++cell) {
    if (cell_exists(kCells, cell)) total += expected[cell] = integrate(c.v, glm::dvec3(c.p), cell_corners(kCells, cell), 16);
  }
  for (double& e : expected) e *= double(b.size()) / total;
  return trs_test::chi_square_test(observed, expected);
}

std::vector<lightsampler::Barycentrics> spherical_points(const Configuration& c, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<lightsampler::Barycentrics> points;
  for (int i = 0; i < kSamples; ++i) {
    const float u1 = lightsampler::uniform_float(std::uint32_t(rng())), u2 = lightsampler::uniform_float(std::uint32_t(rng()));
    const lightsampler::Barycentrics b = sample_spherical_triangle(c.v, c.p, u1, u2);
    EXPECT_TRUE(b.b1 >= 0.0f && b.b2 >= 0.0f && 1.0f - b.b1 - b.b2 >= 0.0f) << b.b1 << " " << b.b2;
    points.push_back(b);
  }
  return points;
}

const double kAlpha = trs_test::sidak_alpha(0.01, kConfigurations.size());

TEST(SphericalTriangle, PointsAreUniformInSolidAngle) {
  for (const Configuration& c : kConfigurations) {
    const double omega = solid_angle(c.v, c.p);
    const trs_test::ChiSquareResult result = test_density(c, spherical_points(c, 1));
    EXPECT_TRUE(result.passes(kAlpha)) << c.name << " (" << omega << " sr)\n" << result.describe();
    EXPECT_GT(result.dof, 100.0) << c.name;
  }
}

TEST(SphericalTriangle, TheCheckRejectsUniformPointsByArea) {
  const Configuration& near = kConfigurations[0];
  std::mt19937_64 rng(2);
  std::vector<lightsampler::Barycentrics> points;
  for (int i = 0; i < kSamples; ++i)
    points.push_back(lightsampler::triangle_map(lightsampler::uniform_float(std::uint32_t(rng())),
                                                lightsampler::uniform_float(std::uint32_t(rng()))));
  EXPECT_FALSE(test_density(near, points).passes(kAlpha));
}

}  // namespace
