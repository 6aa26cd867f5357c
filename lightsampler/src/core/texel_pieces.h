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
#include <optional>

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

/// The lattice cells [x0, x1] x [y0, y1] that for_each_texel_piece visits: the triangle's
/// bounding box or, for a triangle without UV area (`flat`), the one cell of its origin, whose
/// piece is the whole triangle. The Vulkan backend keeps a CDF over these cells, row by row.
struct PieceCells {
  std::int64_t x0, y0, x1, y1;
  bool flat;
  std::uint64_t count() const { return std::uint64_t(x1 - x0 + 1) * std::uint64_t(y1 - y0 + 1); }
};

inline PieceCells piece_cells(const TexelTriangle& t) {
  const double ox = t.origin[0], oy = t.origin[1];
  const double e1x = t.edge1[0], e1y = t.edge1[1], e2x = t.edge2[0], e2y = t.edge2[1];
  if (e1x * e2y - e1y * e2x == 0.0) {
    const std::int64_t ix = floor_to_int(t.origin[0]), iy = floor_to_int(t.origin[1]);
    return {ix, iy, ix, iy, true};
  }
  const double xs[3] = {ox, ox + e1x, ox + e2x}, ys[3] = {oy, oy + e1y, oy + e2y};
  return {std::int64_t(std::floor(std::min({xs[0], xs[1], xs[2]}))),
          std::int64_t(std::floor(std::min({ys[0], ys[1], ys[2]}))),
          std::int64_t(std::floor(std::max({xs[0], xs[1], xs[2]}))),
          std::int64_t(std::floor(std::max({ys[0], ys[1], ys[2]}))), false};
}

/// The whole triangle, in its barycentric plane.
inline BaryPolygon unit_simplex() {
  BaryPolygon simplex;
  simplex.v[0] = {0.0, 0.0};
  simplex.v[1] = {1.0, 0.0};
  simplex.v[2] = {0.0, 1.0};
  simplex.n = 3;
  return simplex;
}

/// The part of the triangle in lattice row iy <= y < iy + 1.
inline BaryPolygon row_polygon(const TexelTriangle& t, std::int64_t iy) {
  const double oy = t.origin[1], e1y = t.edge1[1], e2y = t.edge2[1];
  return clip(clip(unit_simplex(), e1y, e2y, oy - double(iy)), -e1y, -e2y, double(iy + 1) - oy);
}

/// The part of a row's polygon in column ix <= x < ix + 1.
inline BaryPolygon cell_polygon(const TexelTriangle& t, const BaryPolygon& row, std::int64_t ix) {
  const double ox = t.origin[0], e1x = t.edge1[0], e2x = t.edge2[0];
  return clip(clip(row, e1x, e2x, ox - double(ix)), -e1x, -e2x, double(ix + 1) - ox);
}

/// The piece of lattice cell (ix, iy), cut exactly as for_each_texel_piece cuts it; none where
/// the triangle does not overlap the cell with non-zero area.
inline std::optional<TexelPiece> texel_piece(const TexelTriangle& t, std::int64_t ix, std::int64_t iy) {
  const PieceCells cells = piece_cells(t);
  if (cells.flat) {
    if (ix != cells.x0 || iy != cells.y0) return std::nullopt;
    return TexelPiece{ix, iy, unit_simplex(), 0.5};
  }
  const BaryPolygon row = row_polygon(t, iy);
  if (row.n < 3) return std::nullopt;
  const BaryPolygon cell = cell_polygon(t, row, ix);
  if (cell.n < 3) return std::nullopt;
  const double area = cell.area();
  if (!(area > 0.0)) return std::nullopt;
  return TexelPiece{ix, iy, cell, area};
}

/// Calls fn(const TexelPiece&) for every lattice cell the triangle overlaps with non-zero area
/// and keep(ix, iy) accepts, row by row; keep spares the clipping of cells the caller would
/// ignore. A triangle without UV area lies in the one cell of its origin.
template <class Fn, class Keep>
void for_each_texel_piece(const TexelTriangle& t, Fn&& fn, Keep&& keep) {
  const PieceCells cells = piece_cells(t);
  if (cells.flat) {
    if (keep(cells.x0, cells.y0)) fn(TexelPiece{cells.x0, cells.y0, unit_simplex(), 0.5});
    return;
  }
  for (std::int64_t iy = cells.y0; iy <= cells.y1; ++iy) {
    const BaryPolygon row = row_polygon(t, iy);
    if (row.n < 3) continue;
    for (std::int64_t ix = cells.x0; ix <= cells.x1; ++ix) {
      if (!keep(ix, iy)) continue;
      const BaryPolygon cell = cell_polygon(t, row, ix);
      if (cell.n < 3) continue;
      const double area = cell.area();
      if (area > 0.0) fn(TexelPiece{ix, iy, cell, area});
    }
  }
}

template <class Fn>
void for_each_texel_piece(const TexelTriangle& t, Fn&& fn) {
  for_each_texel_piece(t, fn, [](std::int64_t, std::int64_t) { return true; });
}

}  // namespace lightsampler::core
