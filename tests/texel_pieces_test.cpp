// Sampler::texel_pieces and Sampler::texel_piece: a triangle cut along the texel lattice, the
// pieces a caller draws exact texel-proportional points from.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "lightsampler/backend.h"
#include "lightsampler/texel_pieces.h"
#include "sampler_fixtures.h"

namespace {

using lightsampler::TexelPiece;

/// Triangles reaching from -1.5 to 2.5 in UV: wrapped and clamped cells, and cells beyond the map.
trs_test::Mesh wide_triangles() { return trs_test::random_triangles(40, -1.5f, 2.5f, 17); }

double world_area(const lightsampler::MeshView& mesh, std::uint32_t t) {
  double p[3][3];
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) p[k][a] = mesh.positions[3 * std::size_t(mesh.indices[3 * t + k]) + a];
  const double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
  const double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// The pieces integrate the density exactly: density times area, summed, is the counting pass's
// N-bar_T (exact too, by the closed-form overlaps), to rounding; and where every texel is lit
// their areas tile the triangle.
TEST(TexelPieces, IntegrateTheDensityAsTheCountingPassDoes) {
  for (auto addressing : {lightsampler::Addressing::wrap, lightsampler::Addressing::clamp,
                          lightsampler::Addressing::mirror}) {
    const trs_test::Mesh mesh = wide_triangles();
    trs_test::Map map = trs_test::random_map(9, 7, 0.3, 5);
    map.addressing = addressing;
    map.scale = 2.5f;
    const lightsampler::DensityMapView view = map.view();
    const auto sampler = lightsampler::make_cpu_sampler(mesh.view(), {&view, 1});
    lightsampler::Frame frame;
    sampler->generate({.seed = 1, .realize = false}, frame);
    std::vector<TexelPiece> pieces;
    for (std::uint32_t t = 0; t < sampler->triangle_count(); ++t) {
      sampler->maps().texel_pieces(t, pieces);
      double integral = 0.0;
      for (const TexelPiece& p : pieces) {
        EXPECT_GT(p.density, 0.0f);
        integral += double(p.density) * p.area;
      }
      integral *= world_area(mesh.view(), t);
      EXPECT_NEAR(integral, frame.expected_counts.span()[t], 1e-6 * frame.expected_counts.span()[t] + 1e-12)
          << "triangle " << t;
    }
  }
  const trs_test::Mesh mesh = wide_triangles();
  const trs_test::Map lit = trs_test::random_map(9, 7, 0.0, 6);
  const lightsampler::DensityMapView view = lit.view();
  const auto sampler = lightsampler::make_cpu_sampler(mesh.view(), {&view, 1});
  std::vector<TexelPiece> pieces;
  for (std::uint32_t t = 0; t < sampler->triangle_count(); ++t) {
    sampler->maps().texel_pieces(t, pieces);
    double area = 0.0;
    for (const TexelPiece& p : pieces) area += p.area;
    EXPECT_NEAR(area, 1.0, 1e-9) << "triangle " << t;
  }
}

// A point drawn in a piece by its cell is the point uniform_point draws in the piece, bit for bit;
// points drawn in it read its texel, and the density it names is what Sampler::density reads there.
TEST(TexelPieces, OneCellIsCutAsTheWholeTriangleCutsIt) {
  const trs_test::Mesh mesh = wide_triangles();
  const trs_test::Map map = trs_test::random_map(9, 7, 0.3, 8);
  const lightsampler::DensityMapView view = map.view();
  const auto sampler = lightsampler::make_cpu_sampler(mesh.view(), {&view, 1});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<TexelPiece> pieces;
  int points = 0, elsewhere = 0;
  for (std::uint32_t t = 0; t < sampler->triangle_count(); ++t) {
    sampler->maps().texel_pieces(t, pieces);
    for (const TexelPiece& p : pieces) {
      for (int i = 0; i < 4; ++i, ++points) {
        const float u_fan = u(rng), u0 = u(rng), u1 = u(rng);
        const lightsampler::Barycentrics b = lightsampler::uniform_point(p, u_fan, u0, u1);
        const auto by_cell = sampler->maps().texel_piece_point(t, p.cell_x, p.cell_y, u_fan, u0, u1);
        ASSERT_TRUE(by_cell.has_value());
        EXPECT_EQ(by_cell->b1, b.b1);
        EXPECT_EQ(by_cell->b2, b.b2);
        const auto texel = sampler->maps().texel(t, b.b1, b.b2);
        ASSERT_TRUE(texel.has_value());
        if (texel->x != p.texel.x || texel->y != p.texel.y) {
          ++elsewhere;  // rounding onto the cell's edge
          continue;
        }
        EXPECT_EQ(sampler->maps().density(t, b.b1, b.b2), p.density);
      }
    }
  }
  EXPECT_GT(points, 1000);
  EXPECT_LE(elsewhere, points / 1000);
  EXPECT_FALSE(sampler->maps().texel_piece_point(0, 1000, 1000, 0.5f, 0.5f, 0.5f).has_value());
}

// Points drawn in a piece are uniform in it: over a fine grid of the barycentric plane, the
// counts of 200,000 points in a piece cut from a texel's corner follow the grid cells' areas
// inside the piece (chi-square, alpha 0.01, seed 4).
TEST(TexelPieces, PointsAreUniformInTheirPiece) {
  trs_test::Mesh mesh;
  const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const float uv[3][2] = {{0.1f, 0.2f}, {0.9f, 0.3f}, {0.3f, 0.95f}};
  mesh.add_triangle(p, uv);
  const trs_test::Map map = trs_test::random_map(2, 2, 0.0, 9);
  const lightsampler::DensityMapView view = map.view();
  const auto sampler = lightsampler::make_cpu_sampler(mesh.view(), {&view, 1});
  std::vector<TexelPiece> pieces;
  sampler->maps().texel_pieces(0, pieces);
  ASSERT_EQ(pieces.size(), 4u);
  const TexelPiece& piece = pieces[0];
  // Area of the piece inside each of G x G bins of [0, 1]^2, by sub-sampling each bin.
  constexpr int G = 12, kSub = 40, kPoints = 200000;
  const auto inside = [&](double b1, double b2) {
    for (std::uint32_t i = 0; i < piece.vertex_count; ++i) {
      const auto& a = piece.vertices[i];
      const auto& b = piece.vertices[(i + 1) % piece.vertex_count];
      if ((b[0] - a[0]) * (b2 - a[1]) - (b[1] - a[1]) * (b1 - a[0]) < 0) return false;
    }
    return true;
  };
  std::vector<double> expected(G * G, 0.0);
  for (int i = 0; i < G * kSub; ++i)
    for (int j = 0; j < G * kSub; ++j)
      if (inside((i + 0.5) / (G * kSub), (j + 0.5) / (G * kSub))) expected[(i / kSub) * G + j / kSub] += 1.0;
  double total = 0.0;
  for (double e : expected) total += e;
  std::vector<double> observed(G * G, 0.0);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int k = 0; k < kPoints; ++k) {
    const auto b = lightsampler::uniform_point(piece, u(rng), u(rng), u(rng));
    observed[std::min(int(b.b1 * G), G - 1) * G + std::min(int(b.b2 * G), G - 1)] += 1.0;
  }
  double chi2 = 0.0;
  int dof = -1;
  for (int c = 0; c < G * G; ++c) {
    const double e = expected[c] / total * kPoints;
    if (e < 20.0) continue;  // edge bins, partly outside: their share by sub-sampling is rough
    chi2 += (observed[c] - e) * (observed[c] - e) / e;
    ++dof;
  }
  ASSERT_GT(dof, 10);
  // The 0.99 quantile of chi-square with dof degrees of freedom (Wilson-Hilferty).
  const double z = 2.326, h = 2.0 / (9.0 * dof);
  EXPECT_LT(chi2, dof * std::pow(1.0 - h + z * std::sqrt(h), 3.0)) << dof << " dof";
}

// Every backend cuts the same pieces: the Vulkan sampler and a refined one give the CPU's.
TEST(TexelPieces, EveryBackendCutsTheSamePieces) {
  const trs_test::Mesh mesh = wide_triangles();
  const trs_test::Map map = trs_test::random_map(9, 7, 0.3, 10);
  const lightsampler::DensityMapView view = map.view();
  const auto cpu = lightsampler::make_cpu_sampler(mesh.view(), {&view, 1});
  const auto refined = lightsampler::make_sampler(
      mesh.view(), {&view, 1}, {.backend = lightsampler::Backend::cpu, .refinement = {.min_acceptance = 0.9f}});
  std::vector<TexelPiece> a, b;
  for (std::uint32_t t = 0; t < cpu->triangle_count(); ++t) {
    cpu->maps().texel_pieces(t, a);
    refined->maps().texel_pieces(t, b);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].vertices, b[i].vertices);
  }
}

}  // namespace
