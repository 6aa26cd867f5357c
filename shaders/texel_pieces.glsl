// The GLSL twin of core/texel_pieces.h, naive stratification's building block: a triangle cut
// along the texel lattice by Sutherland–Hodgman clipping in its barycentric plane (b1, b2), where
// it is the unit simplex and a texel is the preimage of its square, so that a point drawn in a
// piece is already a sample's barycentrics. The host's double operations in the host's order,
// precise (no fused multiply-add): the same pieces as the CPU backend's wherever the device
// rounds double arithmetic as IEEE 754 does.
#ifndef LIGHTSAMPLER_TEXEL_PIECES_GLSL
#define LIGHTSAMPLER_TEXEL_PIECES_GLSL

#include "common.glsl"

// A triangle clipped by four half-planes has at most seven vertices.
const int kMaxPolygonVertices = 7;

// A convex polygon of the barycentric plane.
struct BaryPolygon {
  dvec2 v[kMaxPolygonVertices];
  int n;
};

BaryPolygon empty_polygon() {
  const dvec2 o = dvec2(0.0lf);
  return BaryPolygon(dvec2[kMaxPolygonVertices](o, o, o, o, o, o, o), 0);
}

BaryPolygon unit_simplex() {
  BaryPolygon s = empty_polygon();
  s.v[1] = dvec2(1.0lf, 0.0lf);
  s.v[2] = dvec2(0.0lf, 1.0lf);
  s.n = 3;
  return s;
}

// Clipping a convex polygon by a line adds at most one vertex; the guard keeps rounding that
// makes nearly collinear vertices look otherwise from writing past the end.
void add_vertex(inout BaryPolygon polygon, dvec2 v) {
  if (polygon.n < kMaxPolygonVertices) {
    polygon.v[polygon.n] = v;
    ++polygon.n;
  }
}

// Area in barycentric units (the whole triangle: 1/2), by the shoelace formula.
double polygon_area(BaryPolygon polygon) {
  precise double twice = 0.0lf;
  for (int i = 0; i < polygon.n; ++i) {
    dvec2 a = polygon.v[i], b = polygon.v[i + 1 < polygon.n ? i + 1 : 0];
    precise double cross = a.x * b.y - a.y * b.x;
    twice += cross;
  }
  return 0.5lf * abs(twice);
}

// Sutherland–Hodgman against the half-plane a0 b1 + a1 b2 + c >= 0.
BaryPolygon clip(BaryPolygon polygon, double a0, double a1, double c) {
  BaryPolygon kept = empty_polygon();
  for (int i = 0; i < polygon.n; ++i) {
    dvec2 p = polygon.v[i], q = polygon.v[i + 1 < polygon.n ? i + 1 : 0];
    precise double dp = a0 * p.x + a1 * p.y + c;
    precise double dq = a0 * q.x + a1 * q.y + c;
    if (dp >= 0.0lf) add_vertex(kept, p);
    if ((dp >= 0.0lf) != (dq >= 0.0lf)) {
      precise double t = dp / (dp - dq);
      precise dvec2 crossing = p + t * (q - p);
      add_vertex(kept, crossing);
    }
  }
  return kept;
}

// A triangle's affine map from barycentrics to texel space, and the lattice cells [x0, x1] x
// [y0, y1] its pieces lie in (core::piece_cells): its bounding box or, with no UV area
// (`uv_flat`), the one cell of its origin, whose piece is the whole triangle.
struct PieceLattice {
  dvec2 origin, edge1, edge2;
  int64_t x0, y0, x1, y1;
  bool uv_flat;
};

PieceLattice piece_lattice(TexelTriangle t) {
  PieceLattice l;
  l.origin = dvec2(t.origin_x, t.origin_y);
  l.edge1 = dvec2(t.edge1_x, t.edge1_y);
  l.edge2 = dvec2(t.edge2_x, t.edge2_y);
  precise double e1x_e2y = l.edge1.x * l.edge2.y, e1y_e2x = l.edge1.y * l.edge2.x;
  l.uv_flat = e1x_e2y - e1y_e2x == 0.0lf;
  precise dvec2 b = l.origin + l.edge1, c = l.origin + l.edge2;
  dvec2 lo = min(l.origin, min(b, c)), hi = max(l.origin, max(b, c));
  // Texel coordinates stay below 2^56 (common.glsl), so the conversions are defined.
  l.x0 = l.uv_flat ? floor_to_int(t.origin_x) : int64_t(floor(lo.x));
  l.y0 = l.uv_flat ? floor_to_int(t.origin_y) : int64_t(floor(lo.y));
  l.x1 = l.uv_flat ? l.x0 : int64_t(floor(hi.x));
  l.y1 = l.uv_flat ? l.y0 : int64_t(floor(hi.y));
  return l;
}

uint64_t lattice_columns(PieceLattice l) { return uint64_t(l.x1 - l.x0 + 1l); }

// The part of the triangle in the row iy <= y < iy + 1.
BaryPolygon row_piece(PieceLattice l, int64_t iy) {
  BaryPolygon above = clip(unit_simplex(), l.edge1.y, l.edge2.y, l.origin.y - double(iy));
  return clip(above, -l.edge1.y, -l.edge2.y, double(iy + 1l) - l.origin.y);
}

// The part of a row's piece in the column ix <= x < ix + 1.
BaryPolygon cell_piece(PieceLattice l, BaryPolygon row, int64_t ix) {
  BaryPolygon right = clip(row, l.edge1.x, l.edge2.x, l.origin.x - double(ix));
  return clip(right, -l.edge1.x, -l.edge2.x, double(ix + 1l) - l.origin.x);
}

// The piece of the triangle in cell (ix, iy) of its lattice: what core::for_each_texel_piece
// clips there, vertex for vertex (fewer than 3 vertices: none).
BaryPolygon lattice_piece(PieceLattice l, int64_t ix, int64_t iy) {
  if (l.uv_flat) return ix == l.x0 && iy == l.y0 ? unit_simplex() : empty_polygon();
  BaryPolygon row = row_piece(l, iy);
  return row.n < 3 ? empty_polygon() : cell_piece(l, row, ix);
}

// The barycentric area of the part of triangle t in lattice cell (ix, iy), as naive
// stratification measures that piece (0: none); twice it is the fraction of the triangle in the
// cell. One (triangle, cell) pair on its own, for passes that visit cells rather than triangles.
double clipped_area(TexelTriangle t, int64_t ix, int64_t iy) {
  BaryPolygon piece = lattice_piece(piece_lattice(t), ix, iy);
  return piece.n < 3 ? 0.0lf : polygon_area(piece);
}

// A triangle's pieces summed: density times barycentric area, and the largest density of a piece.
struct PieceSums {
  double weight;
  float bound;
};

// Walks the pieces of triangle t (which has a map) row by row, as core::for_each_texel_piece,
// and writes the weight summed so far at every cell of its lattice box, row-major: `cells`
// doubles from address `cdf` (the CDF that realization searches; the last is the total).
PieceSums walk_texel_pieces(TexelTriangle t, DensityMap map, uint64_t texels, uint64_t cdf, uint64_t cells) {
  PieceLattice l = piece_lattice(t);
  PieceSums sums = PieceSums(0.0lf, 0.0);
  uint64_t j = 0ul;  // the cell's index in the box
  for (int64_t iy = l.y0; iy <= l.y1; ++iy) {
    // One row clipped for all its cells, as the host clips it.
    BaryPolygon row = l.uv_flat ? unit_simplex() : row_piece(l, iy);
    for (int64_t ix = l.x0; ix <= l.x1; ++ix, ++j) {
      BaryPolygon piece = l.uv_flat ? row : row.n < 3 ? empty_polygon() : cell_piece(l, row, ix);
      double area = piece.n < 3 ? 0.0lf : polygon_area(piece);
      if (area > 0.0lf) {
        float density = cell_density(map, texels, ix, iy);
        precise double weight = double(density) * area;
        sums.weight += weight;
        sums.bound = max(sums.bound, density);
      }
      if (j < cells) Doubles(cdf + j * 8ul).v[0] = sums.weight;
    }
  }
  return sums;
}

#endif
