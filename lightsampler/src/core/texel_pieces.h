#pragma once
// Naive triangle stratification's building block (paper, Section 3.2, and the baseline of its
// Section 6): a triangle cut along the texel lattice by ordinary polygon clipping, one piece per
// texel it overlaps. The clipping runs in the triangle's barycentric plane (b1, b2), where the
// triangle is the unit simplex and a texel is the preimage of its square under the triangle's
// affine map, so that a point drawn in a piece is already a sample's barycentrics. The GLSL twin
// is shaders/texel_pieces.glsl.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/density.h"
#include "core/geometry.h"

namespace lightsampler::core {

/// A convex polygon of the barycentric plane: a triangle clipped by four half-planes has at most
/// seven vertices.
struct BaryPolygon {
  std::array<std::array<double, 2>, 7> v{};
  int n = 0;

  /// Area in barycentric units (the whole triangle: 1/2), by the shoelace formula.
  double area() const {
    double twice = 0.0;
    for (int i = 0; i < n; ++i) {
      const auto& a = v[i];
      const auto& b = v[(i + 1) % n];
      twice += a[0] * b[1] - a[1] * b[0];
    }
    return 0.5 * std::abs(twice);
  }
};

/// The part of a triangle in lattice cell (ix, iy).
struct TexelPiece {
  std::int64_t ix, iy;
  BaryPolygon polygon;
  double area;  ///< barycentric units: twice the area is the fraction of the triangle
};

/// Sutherland–Hodgman against the half-plane a0 b1 + a1 b2 + c >= 0.
inline BaryPolygon clip(const BaryPolygon& in, double a0, double a1, double c) {
  BaryPolygon out;
  for (int i = 0; i < in.n; ++i) {
    const auto& p = in.v[i];
    const auto& q = in.v[(i + 1) % in.n];
    const double dp = a0 * p[0] + a1 * p[1] + c, dq = a0 * q[0] + a1 * q[1] + c;
    if (dp >= 0) out.v[out.n++] = p;
    if ((dp >= 0) != (dq >= 0)) {
      const double t = dp / (dp - dq);
      out.v[out.n++] = {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])};
    }
  }
  return out;
}

/// Calls fn(const TexelPiece&) for every lattice cell the triangle overlaps with non-zero area,
/// row by row. A triangle without UV area lies in the one cell of its origin.
template <class Fn>
void for_each_texel_piece(const TexelTriangle& t, Fn&& fn) {
  const double ox = t.origin[0], oy = t.origin[1];
  const double e1x = t.edge1[0], e1y = t.edge1[1], e2x = t.edge2[0], e2y = t.edge2[1];
  BaryPolygon simplex;
  simplex.v[0] = {0.0, 0.0};
  simplex.v[1] = {1.0, 0.0};
  simplex.v[2] = {0.0, 1.0};
  simplex.n = 3;
  if (e1x * e2y - e1y * e2x == 0.0) {
    fn(TexelPiece{floor_to_int(t.origin[0]), floor_to_int(t.origin[1]), simplex, 0.5});
    return;
  }
  const double xs[3] = {ox, ox + e1x, ox + e2x}, ys[3] = {oy, oy + e1y, oy + e2y};
  const auto x0 = std::int64_t(std::floor(std::min({xs[0], xs[1], xs[2]})));
  const auto x1 = std::int64_t(std::floor(std::max({xs[0], xs[1], xs[2]})));
  const auto y0 = std::int64_t(std::floor(std::min({ys[0], ys[1], ys[2]})));
  const auto y1 = std::int64_t(std::floor(std::max({ys[0], ys[1], ys[2]})));
  for (std::int64_t iy = y0; iy <= y1; ++iy) {
    // The row iy <= y < iy + 1, then each cell ix <= x < ix + 1 of it.
    const BaryPolygon row = clip(clip(simplex, e1y, e2y, oy - double(iy)), -e1y, -e2y, double(iy + 1) - oy);
    if (row.n < 3) continue;
    for (std::int64_t ix = x0; ix <= x1; ++ix) {
      const BaryPolygon cell = clip(clip(row, e1x, e2x, ox - double(ix)), -e1x, -e2x, double(ix + 1) - ox);
      if (cell.n < 3) continue;
      const double area = cell.area();
      if (area > 0.0) fn(TexelPiece{ix, iy, cell, area});
    }
  }
}

}  // namespace lightsampler::core
