// The closed-form triangle/rectangle overlap (lightsampler/overlap.h, the paper's Section 4)
// against an independent oracle: Sutherland–Hodgman clipping plus the shoelace formula
// (support/polygon_clip.h). Random cases use std::mt19937_64 with fixed seeds.
//
// Tolerance, double: 1e-14 absolute at unit scale (unit texel, coordinates within a few texels of
// it), i.e. ~50 ulp of a texel's area. Both methods work relative to the rectangle's corner, so
// the error grows with the triangle's extent measured from that corner and with the rectangle's
// size, not with the absolute position: the bound is 1e-14 * S * max(1, w, h), with
// S = max(1, w, h, |vertex - corner|). The worst measured case over all tests below is 5% of it.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "core/overlap_variants.h"
#include "core/texel_pieces.h"
#include "lightsampler/overlap.h"
#include "support/polygon_clip.h"

namespace {

using trs_test::Point;

struct Rect {
  double x0, y0, x1, y1;
};

struct Triangle {
  Point a, b, c;
  Triangle reversed() const { return {a, c, b}; }
  Triangle rotated() const { return {b, c, a}; }
};

double closed_form(const Triangle& t, const Rect& r) {
  const double a[2] = {t.a.x, t.a.y}, b[2] = {t.b.x, t.b.y}, c[2] = {t.c.x, t.c.y};
  return lightsampler::rect_triangle_overlap(a, b, c, r.x0, r.y0, r.x1, r.y1);
}

double oracle(const Triangle& t, const Rect& r) {
  return trs_test::clipped_triangle_area(t.a, t.b, t.c, r.x0, r.y0, r.x1, r.y1);
}

/// Relative to a vertex, so that the products stay at the triangle's scale, not the coordinates'.
double triangle_area(const Triangle& t) {
  return 0.5 * std::abs((t.b.x - t.a.x) * (t.c.y - t.a.y) - (t.b.y - t.a.y) * (t.c.x - t.a.x));
}

double tolerance(const Triangle& t, const Rect& r) {
  const double w = r.x1 - r.x0, h = r.y1 - r.y0;
  double extent = std::max({1.0, w, h});
  for (const Point& p : {t.a, t.b, t.c}) extent = std::max({extent, std::abs(p.x - r.x0), std::abs(p.y - r.y0)});
  return 1e-14 * extent * std::max({1.0, w, h});
}

std::string describe(const Triangle& t, const Rect& r) {
  char text[400];
  std::snprintf(text, sizeof text, "triangle (%.17g, %.17g) (%.17g, %.17g) (%.17g, %.17g), rectangle [%.17g, %.17g] x [%.17g, %.17g]",
                t.a.x, t.a.y, t.b.x, t.b.y, t.c.x, t.c.y, r.x0, r.x1, r.y0, r.y1);
  return text;
}

/// Largest error relative to the tolerance over many cases, and the case that produced it: one
/// readable failure instead of thousands.
class Worst {
 public:
  void check(const Triangle& t, const Rect& r) {
    const double expected = oracle(t, r);
    // Both orientations and every starting vertex describe the same triangle.
    for (const Triangle& u : {t, t.rotated(), t.rotated().rotated(), t.reversed(), t.reversed().rotated(),
                              t.reversed().rotated().rotated()}) {
      const double got = closed_form(u, r);
      const double ratio = std::isfinite(got) ? std::abs(got - expected) / tolerance(u, r) : INFINITY;
      if (!(ratio <= worst_ratio_)) {
        worst_ratio_ = ratio;
        char numbers[200];
        std::snprintf(numbers, sizeof numbers, ": expected %.17g, got %.17g, tolerance %.3g", expected, got, tolerance(u, r));
        worst_case_ = describe(u, r) + numbers;
      }
    }
    ++cases_;
  }
  /// Passes when every case was within its tolerance.
  void expect_within_tolerance() const {
    EXPECT_LE(worst_ratio_, 1.0) << "worst of " << cases_ << " cases: " << worst_case_;
    EXPECT_GT(cases_, 0);
  }

 private:
  double worst_ratio_ = 0;
  std::string worst_case_;
  int cases_ = 0;
};

Point random_point(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> d(lo, hi);
  return {d(rng), d(rng)};
}

const Rect kUnitTexel = {0, 0, 1, 1};

TEST(Overlap, HandComputedAreas) {
  // Right triangle (0,0) (2,0) (0,2): the hypotenuse x + y = 2 leaves texel (0,0) whole, halves
  // (1,0) and (0,1), and touches (1,1) only at its corner.
  const Triangle t = {{0, 0}, {2, 0}, {0, 2}};
  const std::array<std::pair<Rect, double>, 5> cases = {{
      {{0, 0, 1, 1}, 1.0},
      {{1, 0, 2, 1}, 0.5},
      {{0, 1, 1, 2}, 0.5},
      {{1, 1, 2, 2}, 0.0},
      {{-1, -1, 3, 3}, 2.0},  // the rectangle holds the whole triangle
  }};
  for (const auto& [r, area] : cases) {
    EXPECT_DOUBLE_EQ(closed_form(t, r), area) << describe(t, r);
    EXPECT_DOUBLE_EQ(closed_form(t.reversed(), r), area) << describe(t.reversed(), r);
    EXPECT_DOUBLE_EQ(oracle(t, r), area) << describe(t, r);
  }
}

TEST(Overlap, HeptagonIntersection) {
  // A triangle whose three edges each cut off one corner of the texel: the intersection is a
  // heptagon, the most complex shape there is. Edge normals at 45, 165 and 285 degrees, inradius 0.55
  // about the texel centre (corners lie 0.707 away), vertices opposite the normals at radius 1.1.
  Triangle t;
  Point* v[3] = {&t.a, &t.b, &t.c};
  const double pi = std::acos(-1.0);
  for (int i = 0; i < 3; ++i) {
    const double angle = (225.0 + 120.0 * i) * pi / 180.0;
    *v[i] = {0.5 + 1.1 * std::cos(angle), 0.5 + 1.1 * std::sin(angle)};
  }
  const trs_test::Polygon clipped = trs_test::clip_to_rectangle({t.a, t.b, t.c}, 0, 0, 1, 1);
  ASSERT_EQ(clipped.size(), 7u);
  Worst worst;
  worst.check(t, kUnitTexel);
  worst.expect_within_tolerance();
}

TEST(Overlap, RandomTrianglesAroundATexel) {
  // General position: vertices uniform in [-1, 2]^2 around texel [0,1]^2, so every shape of
  // intersection (empty to heptagon) occurs. Seed 1.
  std::mt19937_64 rng(1);
  Worst worst;
  for (int i = 0; i < 20000; ++i) {
    worst.check({random_point(rng, -1, 2), random_point(rng, -1, 2), random_point(rng, -1, 2)}, kUnitTexel);
  }
  worst.expect_within_tolerance();
}

TEST(Overlap, SliverTriangles) {
  // Very thin triangles: c lies off the line ab by 1e-3 down to 1e-15 of |ab|, across the texel.
  // Seed 2.
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> along(-0.5, 1.5), exponent(-15, -3);
  Worst worst;
  for (int i = 0; i < 20000; ++i) {
    const Point a = random_point(rng, -1, 2), b = random_point(rng, -1, 2);
    const double s = along(rng), offset = std::pow(10.0, exponent(rng));
    const Point c = {a.x + s * (b.x - a.x) - offset * (b.y - a.y), a.y + s * (b.y - a.y) + offset * (b.x - a.x)};
    worst.check({a, b, c}, kUnitTexel);
  }
  worst.expect_within_tolerance();
}

TEST(Overlap, TriangleInsideOneTexel) {
  // The whole triangle lies inside the texel: the overlap is the triangle's area. Seed 3.
  std::mt19937_64 rng(3);
  Worst worst;
  for (int i = 0; i < 5000; ++i) {
    const Triangle t = {random_point(rng, 0, 1), random_point(rng, 0, 1), random_point(rng, 0, 1)};
    EXPECT_NEAR(closed_form(t, kUnitTexel), triangle_area(t), 1e-14) << describe(t, kUnitTexel);
    worst.check(t, kUnitTexel);
  }
  worst.expect_within_tolerance();
}

TEST(Overlap, TexelInsideLargeTriangle) {
  // A triangle with vertices 50 to 1000 texels away in three directions holds the texel whole.
  // Seed 4.
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> radius(50, 1000), jitter(-0.3, 0.3);
  const double pi = std::acos(-1.0);
  Worst worst;
  for (int i = 0; i < 5000; ++i) {
    Triangle t;
    Point* v[3] = {&t.a, &t.b, &t.c};
    for (int k = 0; k < 3; ++k) {
      const double angle = 2 * pi * k / 3 + jitter(rng), r = radius(rng);
      *v[k] = {0.5 + r * std::cos(angle), 0.5 + r * std::sin(angle)};
    }
    EXPECT_NEAR(closed_form(t, kUnitTexel), 1.0, tolerance(t, kUnitTexel)) << describe(t, kUnitTexel);
    worst.check(t, kUnitTexel);
  }
  worst.expect_within_tolerance();
}

TEST(Overlap, AxisAlignedEdgesAndVerticesOnTexelBoundaries) {
  // Vertices on a quarter-texel grid: many lie exactly on texel edges and corners, many edges are
  // exactly horizontal or vertical, and many triangles are degenerate. Seed 5.
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> quarter(-4, 8);
  auto grid_point = [&] { return Point{quarter(rng) / 4.0, quarter(rng) / 4.0}; };
  Worst worst;
  for (int i = 0; i < 20000; ++i) worst.check({grid_point(), grid_point(), grid_point()}, kUnitTexel);
  // Axis-aligned right triangles with both legs on texel boundaries.
  for (int i = 0; i < 5000; ++i) {
    const Point a = grid_point(), b = grid_point();
    worst.check({a, {b.x, a.y}, {a.x, b.y}}, kUnitTexel);
  }
  worst.expect_within_tolerance();
}

TEST(Overlap, FarFromTheOrigin) {
  // Texel (4000, 4000) and a 4096-texel map's last texel: the result must not lose the digits
  // that the coordinates spend on their magnitude. Seed 6.
  std::mt19937_64 rng(6);
  Worst worst;
  for (const double corner : {4000.0, 4095.0, 65535.0}) {
    const Rect texel = {corner, corner, corner + 1, corner + 1};
    for (int i = 0; i < 5000; ++i) {
      worst.check({random_point(rng, corner - 1, corner + 2), random_point(rng, corner - 1, corner + 2),
                   random_point(rng, corner - 1, corner + 2)},
                  texel);
    }
  }
  worst.expect_within_tolerance();
}

TEST(Overlap, DegenerateTrianglesHaveZeroArea) {
  // Repeated vertices, and a midpoint that is exactly on its segment (all values dyadic).
  const Point p = {0.25, 0.5}, q = {0.75, 0.125}, mid = {0.5, 0.3125};
  for (const Triangle& t : {Triangle{p, p, q}, Triangle{p, q, q}, Triangle{p, p, p}, Triangle{p, mid, q}}) {
    EXPECT_EQ(closed_form(t, kUnitTexel), 0.0) << describe(t, kUnitTexel);
    EXPECT_EQ(closed_form(t.reversed(), kUnitTexel), 0.0) << describe(t, kUnitTexel);
  }
  // Collinear up to rounding: the cross product may not vanish, the area must still be ~0.
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> s(-1, 2);
  for (int i = 0; i < 5000; ++i) {
    const Point a = random_point(rng, -1, 2), b = random_point(rng, -1, 2);
    const double t = s(rng);
    const Triangle line = {a, b, {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}};
    EXPECT_LE(closed_form(line, kUnitTexel), 1e-15) << describe(line, kUnitTexel);
  }
}

TEST(Overlap, EmptyRectangleHasZeroOverlap) {
  const Triangle t = {{-1, -1}, {3, 0}, {0, 3}};
  EXPECT_EQ(closed_form(t, {0.5, 0.5, 0.5, 1}), 0.0);  // zero width
  EXPECT_EQ(closed_form(t, {0.5, 0.5, 1, 0.5}), 0.0);  // zero height
  EXPECT_EQ(closed_form(t, {1, 1, 0, 0}), 0.0);        // inverted
}

TEST(Overlap, NonUnitRectangles) {
  // Rectangles from 1e-6 to 100 wide and high, independently (thin strips included), with
  // triangles at the scale of the rectangle. Seed 9.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> exponent(-6, 2), corner(-10, 10);
  Worst worst;
  for (int i = 0; i < 20000; ++i) {
    const double w = std::pow(10.0, exponent(rng)), h = std::pow(10.0, exponent(rng));
    const double x0 = corner(rng), y0 = corner(rng);
    const Rect rect = {x0, y0, x0 + w, y0 + h};
    const double size = std::max(w, h);
    auto around = [&] {
      return Point{rect.x0 + w / 2 + size * std::uniform_real_distribution<double>(-1.5, 1.5)(rng),
                   rect.y0 + h / 2 + size * std::uniform_real_distribution<double>(-1.5, 1.5)(rng)};
    };
    worst.check({around(), around(), around()}, rect);
  }
  worst.expect_within_tolerance();
}

TEST(Overlap, TexelsPartitionTheTriangle) {
  // Summed over every texel it touches, the overlap is the triangle's area: no part counted twice
  // or missed, whatever the triangle. Bound: 1e-14 per texel summed (measured 2.5e-16 per texel,
  // 1.1e-13 in all for a 40-texel triangle). Seed 10.
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> size(0.01, 40);
  for (int i = 0; i < 200; ++i) {
    const double s = size(rng);
    const Triangle t = {random_point(rng, 100, 100 + s), random_point(rng, 100, 100 + s), random_point(rng, 100, 100 + s)};
    const double x_lo = std::floor(std::min({t.a.x, t.b.x, t.c.x})), x_hi = std::ceil(std::max({t.a.x, t.b.x, t.c.x}));
    const double y_lo = std::floor(std::min({t.a.y, t.b.y, t.c.y})), y_hi = std::ceil(std::max({t.a.y, t.b.y, t.c.y}));
    const double a[2] = {t.a.x, t.a.y}, b[2] = {t.b.x, t.b.y}, c[2] = {t.c.x, t.c.y};
    double sum = 0;
    int texels = 0;
    for (double y = y_lo; y < y_hi; ++y) {
      for (double x = x_lo; x < x_hi; ++x, ++texels) sum += lightsampler::texel_overlap(a, b, c, x, y);
    }
    EXPECT_NEAR(sum, triangle_area(t), 1e-14 * texels) << describe(t, {x_lo, y_lo, x_hi, y_hi});
  }
}

TEST(Overlap, OracleTexelAreasPartitionTheTriangle) {
  // The helper the distribution tests use for expected counts: its texels' areas add up to the
  // triangle's, inside the map and out of it (wrap and clamp), and each agrees with texel_overlap
  // where the triangle lies inside the map. Measured: 1.4e-13 for the sums (triangles up to 28
  // texels across), 1e-15 per texel. Seed 11.
  std::mt19937_64 rng(11);
  for (const auto addressing : {lightsampler::Addressing::wrap, lightsampler::Addressing::clamp,
                                 lightsampler::Addressing::mirror}) {
    for (int i = 0; i < 100; ++i) {
      const Triangle t = {random_point(rng, -6, 22), random_point(rng, -6, 22), random_point(rng, -6, 22)};
      const auto areas = trs_test::texel_areas(t.a, t.b, t.c, 16, 8, addressing);
      double sum = 0;
      for (const auto& texel : areas) {
        ASSERT_LT(texel.x, 16u);
        ASSERT_LT(texel.y, 8u);
        sum += texel.area;
      }
      EXPECT_NEAR(sum, triangle_area(t), 1e-11) << describe(t, {0, 0, 16, 8});
    }
  }
  const Triangle inside = {{0.5, 0.25}, {13.75, 1.5}, {6.125, 7.5}};
  for (const auto& texel : trs_test::texel_areas(inside.a, inside.b, inside.c, 16, 8, lightsampler::Addressing::wrap)) {
    const Rect r = {double(texel.x), double(texel.y), texel.x + 1.0, texel.y + 1.0};
    EXPECT_NEAR(texel.area, closed_form(inside, r), 1e-14) << texel.x << ", " << texel.y;
  }
}

TEST(Overlap, FloatInstantiation) {
  // rect_triangle_overlap<float> (the GPU's precision) against the double oracle on the same float
  // inputs. The error is about FLT_EPSILON times the triangle's extent S from the texel corner
  // (the edge terms integrate |x| over the edge, x up to S), whatever the absolute position.
  // Measured over 2e6 triangles per setting: 3.0e-7 at unit scale (S ~ 2), 1.3e-5 for triangles
  // 200 texels across (S ~ 100); at texel 4000, 1.9e-7 and 7.4e-6. Bound: 8 * FLT_EPSILON * S,
  // 4 to 7 times the measured worst. Seed 12.
  std::mt19937_64 rng(12);
  for (const float corner : {0.0f, 4000.0f}) {
    for (const float spread : {1.0f, 100.0f}) {
      std::uniform_real_distribution<float> d(corner - spread, corner + 1 + spread);
      double worst_ratio = 0;
      std::string worst_case;
      for (int i = 0; i < 20000; ++i) {
        const float a[2] = {d(rng), d(rng)}, b[2] = {d(rng), d(rng)}, c[2] = {d(rng), d(rng)};
        const float got = lightsampler::texel_overlap(a, b, c, corner, corner);
        const Triangle t = {{a[0], a[1]}, {b[0], b[1]}, {c[0], c[1]}};
        const Rect r = {corner, corner, corner + 1.0, corner + 1.0};
        double extent = 1;
        for (const Point& p : {t.a, t.b, t.c}) extent = std::max({extent, std::abs(p.x - corner), std::abs(p.y - corner)});
        const double bound = 8 * FLT_EPSILON * extent;
        const double ratio = std::abs(double(got) - oracle(t, r)) / bound;
        if (!(ratio <= worst_ratio)) {
          worst_ratio = ratio;
          char numbers[120];
          std::snprintf(numbers, sizeof numbers, ": got %.9g, expected %.17g, bound %.3g", got, oracle(t, r), bound);
          worst_case = describe(t, r) + numbers;
        }
      }
      EXPECT_LE(worst_ratio, 1.0) << worst_case;
    }
  }
}

TEST(Overlap, NearlyFlatEdgesStayFinite) {
  // An edge whose y-span is so small that dx/dy overflows (a vertex on the texel's bottom edge,
  // the next one a denormal above it) once made the overlap NaN through 0 * inf.
  const double a[2] = {0, 0}, b[2] = {1000, 1e-320}, c[2] = {0.5, 0.5};
  const double expected = trs_test::clipped_triangle_area({0, 0}, {1000, 1e-320}, {0.5, 0.5}, 0, 0, 1, 1);
  EXPECT_NEAR(lightsampler::texel_overlap(a, b, c, 0.0, 0.0), expected, 1e-14);
  const float af[2] = {0, 0}, bf[2] = {1000, 1e-36f}, cf[2] = {0.5f, 0.5f};
  const double float_bound = 8 * FLT_EPSILON * 1000;  // FloatInstantiation's bound, extent 1000
  EXPECT_NEAR(lightsampler::texel_overlap(af, bf, cf, 0.0f, 0.0f), expected, float_bound);
  EXPECT_NEAR(lightsampler::texel_overlap(bf, af, cf, 0.0f, 0.0f), expected, float_bound);
}

}  // namespace

// Naive stratification's clipper (core/texel_pieces.h) cuts a triangle in its barycentric plane;
// mapped to texel space, each piece has the area the texel-space clipping oracle gives its cell,
// no cell with overlap is missed, and the pieces tile the triangle. 300 random triangles (seed
// 17) up to 12 texels across, anywhere in [-4, 12]^2.
TEST(Overlap, TexelPiecesAgreeWithTexelSpaceClipping) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<float> corner(-4.0f, 12.0f), offset(-6.0f, 6.0f);
  for (int n = 0; n < 300; ++n) {
    lightsampler::core::TexelTriangle t{{corner(rng), corner(rng)}, {offset(rng), offset(rng)},
                                        {offset(rng), offset(rng)}, 0};
    const double cross = double(t.edge1[0]) * t.edge2[1] - double(t.edge1[1]) * t.edge2[0];
    if (std::abs(cross) < 1e-3) continue;
    const Point a{t.origin[0], t.origin[1]};
    const Point b{a.x + t.edge1[0], a.y + t.edge1[1]}, c{a.x + t.edge2[0], a.y + t.edge2[1]};
    std::map<std::pair<std::int64_t, std::int64_t>, double> pieces;
    double total = 0.0;
    lightsampler::core::for_each_texel_piece(t, [&](const lightsampler::core::TexelPiece& piece) {
      pieces[{piece.ix, piece.iy}] = piece.area * std::abs(cross);
      total += piece.area;
    });
    EXPECT_NEAR(total, 0.5, 1e-12) << "triangle " << n;
    const auto x0 = std::int64_t(std::floor(std::min({a.x, b.x, c.x}))), x1 = std::int64_t(std::floor(std::max({a.x, b.x, c.x})));
    const auto y0 = std::int64_t(std::floor(std::min({a.y, b.y, c.y}))), y1 = std::int64_t(std::floor(std::max({a.y, b.y, c.y})));
    for (std::int64_t iy = y0; iy <= y1; ++iy) {
      for (std::int64_t ix = x0; ix <= x1; ++ix) {
        const double want = clipped_triangle_area(a, b, c, double(ix), double(iy), double(ix + 1), double(iy + 1));
        const auto it = pieces.find({ix, iy});
        const double got = it == pieces.end() ? 0.0 : it->second;
        EXPECT_NEAR(got, want, 1e-9 * std::abs(cross)) << "triangle " << n << ", cell " << ix << " " << iy;
      }
    }
  }
}

// The alternatives the paper measures the closed form against (core/overlap_variants.h). Polygon
// clipping is exact: it agrees with the closed form within the same tolerance on the random
// cases of RandomTrianglesAroundATexel (seed 1).
TEST(OverlapVariants, ClippingAgreesWithTheClosedForm) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 20000; ++i) {
    const Triangle t = {random_point(rng, -1, 2), random_point(rng, -1, 2), random_point(rng, -1, 2)};
    const double x[3] = {t.a.x, t.b.x, t.c.x}, y[3] = {t.a.y, t.b.y, t.c.y};
    ASSERT_NEAR(lightsampler::core::clipped_overlap(x, y, 0, 0, 1, 1), closed_form(t, kUnitTexel),
                tolerance(t, kUnitTexel))
        << describe(t, kUnitTexel);
  }
}

// Eq. 6 is right where a straight edge crosses a unit cell through its centre or misses it, and
// wrong for a triangle smaller than the cell: the artefact of the paper's Figure 12.
TEST(OverlapVariants, SdfApproximation) {
  using lightsampler::core::sdf_overlap;
  const double x[3] = {0, 2, 0}, y[3] = {0, 0, 2};  // the hypotenuse x + y = 2
  EXPECT_DOUBLE_EQ(sdf_overlap(x, y, 0, 0, 1, 1), 1.0);   // centre 0.707 inside
  EXPECT_DOUBLE_EQ(sdf_overlap(x, y, 1, 0, 2, 1), 0.5);   // the edge through the centre
  EXPECT_DOUBLE_EQ(sdf_overlap(x, y, 1, 1, 2, 2), 0.0);   // centre 0.707 outside
  EXPECT_DOUBLE_EQ(sdf_overlap(x, y, 5, 5, 6, 6), 0.0);
  // Either orientation.
  const double xr[3] = {0, 0, 2}, yr[3] = {0, 2, 0};
  EXPECT_DOUBLE_EQ(sdf_overlap(xr, yr, 1, 0, 2, 1), 0.5);
  // A triangle of area 0.02 whose hypotenuse passes through the cell's centre counts as half the cell.
  const double sx[3] = {0.4, 0.6, 0.4}, sy[3] = {0.4, 0.4, 0.6};
  EXPECT_NEAR(sdf_overlap(sx, sy, 0, 0, 1, 1), 0.5, 1e-15);
  EXPECT_NEAR(lightsampler::core::clipped_overlap(sx, sy, 0, 0, 1, 1), 0.02, 1e-15);
}
