// The counting pass: N-bar_T and D_T^max against an independent computation (polygon clipping
// and the shoelace formula, texel by texel), for both addressing modes and UVs beyond [0, 1].

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "lightsampler/sampler.h"
#include "sampler_fixtures.h"
#include "support/polygon_clip.h"

using namespace lightsampler;

namespace {

struct Reference {
  double expected;
  float max_density;
};

/// Eq. 1-2 by clipping: sum over texels of D(p) Area(p n T_uv), times Area(T) / Area(T_uv).
Reference reference_integral(const trs_test::Mesh& mesh, const trs_test::Map& map, std::size_t t) {
  trs_test::Point p[3];
  double world[3][3];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = mesh.indices[3 * t + k];
    p[k] = {double(mesh.uvs[2 * v]) * map.width, double(mesh.uvs[2 * v + 1]) * map.height};
    for (int a = 0; a < 3; ++a) world[k][a] = mesh.positions[3 * v + a];
  }
  const double e1[3] = {world[1][0] - world[0][0], world[1][1] - world[0][1], world[1][2] - world[0][2]};
  const double e2[3] = {world[2][0] - world[0][0], world[2][1] - world[0][1], world[2][2] - world[0][2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double uv_area = 0.5 * std::abs((p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x));
  Reference r{0, 0};
  for (const auto& texel : trs_test::texel_areas(p[0], p[1], p[2], map.width, map.height, map.addressing)) {
    const float d = map.texels[std::size_t(texel.y) * map.width + texel.x] * map.scale;
    r.expected += double(d) * texel.area;
    r.max_density = std::max(r.max_density, d);
  }
  r.expected *= area / uv_area;
  return r;
}

/// The counting pass alone (no samples) on the CPU backend.
Frame count_only(const trs_test::Mesh& mesh, const trs_test::Map& map, unsigned threads = 0) {
  const DensityMapView view = map.view();
  Frame frame;
  make_cpu_sampler(mesh.view(), {&view, 1}, {threads})->generate({.realize = false}, frame);
  return frame;
}

void expect_matches_reference(const trs_test::Mesh& mesh, const trs_test::Map& map) {
  const Frame frame = count_only(mesh, map);
  double total = 0;
  for (std::size_t t = 0; t < frame.expected_counts.size(); ++t) {
    const Reference r = reference_integral(mesh, map, t);
    // Relative 1e-9: both are exact in real arithmetic; the difference is rounding only.
    EXPECT_NEAR(frame.expected_counts[t], r.expected, 1e-9 * std::max(1.0, r.expected)) << "triangle " << t;
    EXPECT_EQ(frame.max_density[t], r.max_density) << "triangle " << t;
    total += r.expected;
  }
  EXPECT_NEAR(frame.expected_total, total, 1e-9 * std::max(1.0, total));
}

}  // namespace

TEST(Counting, MatchesClippingInsideTheUnitSquare) {
  expect_matches_reference(trs_test::random_triangles(300, 0.0f, 1.0f, 1), trs_test::random_map(37, 23, 0.4, 2));
}

TEST(Counting, MatchesClippingWithWrapBeyondTheUnitSquare) {
  expect_matches_reference(trs_test::random_triangles(200, -1.5f, 2.5f, 3), trs_test::random_map(16, 9, 0.3, 4));
}

TEST(Counting, MatchesClippingWithClampBeyondTheUnitSquare) {
  trs_test::Map map = trs_test::random_map(16, 9, 0.3, 6);
  map.addressing = Addressing::clamp;
  expect_matches_reference(trs_test::random_triangles(200, -1.5f, 2.5f, 5), map);
}

TEST(Counting, MatchesClippingWithMirrorBeyondTheUnitSquare) {
  trs_test::Map map = trs_test::random_map(16, 9, 0.3, 11);
  map.addressing = Addressing::mirror;
  expect_matches_reference(trs_test::random_triangles(200, -1.5f, 2.5f, 12), map);
}

// Mirror addressing reads what wrap reads of the image built by hand from the map and its
// mirror images (twice as wide and high): the same triangles with their UVs halved integrate
// to the same N-bar_T, to rounding.
TEST(Counting, MirrorIsWrapOverTheMirroredImageBuiltByHand) {
  trs_test::Map map = trs_test::random_map(16, 9, 0.3, 13);
  map.addressing = Addressing::mirror;
  trs_test::Map mirrored{std::vector<float>(4 * map.texels.size()), 2 * map.width, 2 * map.height};
  for (std::uint32_t y = 0; y < mirrored.height; ++y) {
    const std::uint32_t sy = y < map.height ? y : mirrored.height - 1 - y;
    for (std::uint32_t x = 0; x < mirrored.width; ++x) {
      const std::uint32_t sx = x < map.width ? x : mirrored.width - 1 - x;
      mirrored.texels[std::size_t(y) * mirrored.width + x] = map.texels[std::size_t(sy) * map.width + sx];
    }
  }
  const trs_test::Mesh mesh = trs_test::random_triangles(200, -1.5f, 2.5f, 14);
  trs_test::Mesh halved = mesh;
  for (float& uv : halved.uvs) uv *= 0.5f;
  const Frame a = count_only(mesh, map), b = count_only(halved, mirrored);
  ASSERT_EQ(a.expected_counts.size(), b.expected_counts.size());
  for (std::size_t t = 0; t < a.expected_counts.size(); ++t)
    EXPECT_NEAR(a.expected_counts[t], b.expected_counts[t], 1e-9 * b.expected_counts[t] + 1e-12) << "triangle " << t;
}

TEST(Counting, SmallTrianglesInsideOneTexelAndSlivers) {
  trs_test::Mesh mesh = trs_test::random_triangles(100, 0.3f, 0.3005f, 7);  // within one texel or two
  const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1e-3f, 0}};
  const float sliver[3][2] = {{0.01f, 0.5f}, {0.99f, 0.5001f}, {0.5f, 0.5003f}};
  mesh.add_triangle(p, sliver);
  expect_matches_reference(mesh, trs_test::random_map(64, 64, 0.2, 8));
}

TEST(Counting, ScaleMultipliesTheDensity) {
  trs_test::Map map = trs_test::random_map(8, 8, 0.0, 9);
  map.scale = 2.5f;
  expect_matches_reference(trs_test::random_triangles(20, 0.0f, 1.0f, 10), map);
}

TEST(Counting, ConstantMapIntegratesToDensityTimesArea) {
  // A 3 x 2 world quad over the whole map, at density 4 per unit area: N-bar = 24.
  const trs_test::Mesh mesh = trs_test::quad(3, 2, 0, 0, 1, 1);
  const trs_test::Map map{std::vector<float>(100 * 70, 4.0f), 100, 70};
  const Frame frame = count_only(mesh, map);
  EXPECT_NEAR(frame.expected_total, 24.0, 1e-10);
  EXPECT_NEAR(frame.expected_counts[0], 12.0, 1e-10);
  EXPECT_EQ(frame.max_density[0], 4.0f);
}

TEST(Counting, HugeTrianglesSplitAcrossTasksGiveTheSameSumOnAnyThreadCount) {
  // Two triangles over a 1024^2 map: each spans ~500k texels, far more than one task's share.
  const trs_test::Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const trs_test::Map map = trs_test::random_map(1024, 1024, 0.5, 11);
  double texel_sum = 0;
  for (float t : map.texels) texel_sum += t;
  std::vector<double> first;
  for (unsigned threads : {1u, 2u}) {
    const Frame frame = count_only(mesh, map, threads);
    // World area 1 spread over 1024^2 texels.
    EXPECT_NEAR(frame.expected_total, texel_sum / (1024.0 * 1024.0), 1e-9 * texel_sum / (1024.0 * 1024.0));
    std::vector<double> counts(frame.expected_counts.begin(), frame.expected_counts.end());
    if (first.empty())
      first = counts;
    else
      EXPECT_EQ(first, counts) << "bitwise identical whatever the thread count";
  }
}
