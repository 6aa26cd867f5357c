// The GLSL twin of core/piece_draw.h: exact draws from a triangle's density, a texel piece in
// proportion to density times area, then a uniform point in it. Naive stratification draws every
// sample so, searching the piece CDF its counting wrote; TRS draws so the rest of a segment
// whose rejection stopped, walking the triangle's pieces for the one to take.
#ifndef LIGHTSAMPLER_PIECE_DRAW_GLSL
#define LIGHTSAMPLER_PIECE_DRAW_GLSL

#include "texel_pieces.glsl"

// A uniform point of a convex polygon of `area`: a triangle of its fan from vertex 0 by area,
// then a uniform point of that triangle. `u` uniform in [0, 1) each.
dvec2 point_in(BaryPolygon polygon, double area, float u_fan, float u0, float u1) {
  dvec2 o = polygon.v[0];
  precise double target = double(u_fan) * area;
  precise double below = 0.0lf;
  int i = 1;
  for (; i < polygon.n - 2; ++i) {
    dvec2 a = polygon.v[i], b = polygon.v[i + 1];
    precise double cross = (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    below += 0.5lf * abs(cross);
    if (target < below) break;
  }
  dvec2 a = polygon.v[i], b = polygon.v[i + 1];
  vec2 s = triangle_map(u0, u1);
  precise dvec2 point = o + double(s.x) * (a - o) + double(s.y) * (b - o);
  return point;
}

// Whether barycentrics b lie in triangle t and read the texel of cell (ix, iy).
bool lands_in(TexelTriangle t, vec2 b, int64_t ix, int64_t iy) {
  precise float sum = b.x + b.y;
  if (!(b.x >= 0.0 && b.y >= 0.0 && sum <= 1.0)) return false;
  vec2 q = texel_space_point(t, b);
  return floor_to_int(q.x) == ix && floor_to_int(q.y) == iy;
}

// The random words of attempt `attempt` at slot k of triangle tri: two draws of four words,
// told apart by bit 31 of the last word (max_tries stays below 2^31).
struct PieceWords {
  uvec4 u, v;
};

PieceWords piece_words(uint tri, uint64_t k, uint attempt, uvec2 key) {
  uvec4 c = uvec4(tri, uint(k), uint(k >> 32), attempt);
  return PieceWords(philox4x32(c, key), philox4x32(uvec4(c.xyz, c.w | 0x80000000u), key));
}

// Where the attempt falls in the triangle's CDF of density times area: a 64-bit uniform times
// the total.
double piece_target(PieceWords w, double total) {
  precise double target = (double(w.u.x) + double(w.u.y) * 4294967296.0lf) * (1.0lf / 18446744073709551616.0lf) * total;
  return target;
}

// The attempt's point in `piece`, the triangle's piece in cell (ix, iy); `landed`: rounding
// left it in that texel.
Sample point_in_piece(uint tri, TexelTriangle t, BaryPolygon piece, int64_t ix, int64_t iy, PieceWords w,
                      out bool landed) {
  dvec2 b = point_in(piece, polygon_area(piece), uniform_float(w.u.z), uniform_float(w.v.x), uniform_float(w.v.y));
  Sample drawn = Sample(tri, float(b.x), float(b.y));
  landed = lands_in(t, vec2(drawn.b1, drawn.b2), ix, iy);
  return drawn;
}

// Density times area of the piece in cell j of lattice l's box, row-major (0: none, or dark);
// dark cells are not clipped.
double piece_weight(PieceLattice l, DensityMap map, uint64_t texels, uint64_t j) {
  int64_t ix = l.x0 + int64_t(j % lattice_columns(l)), iy = l.y0 + int64_t(j / lattice_columns(l));
  float density = cell_density(map, texels, ix, iy);
  if (density <= 0.0) return 0.0lf;
  BaryPolygon piece = lattice_piece(l, ix, iy);
  double area = piece.n < 3 ? 0.0lf : polygon_area(piece);
  precise double weight = double(density) * area;
  return weight;
}

// A walk of the whole subgroup over the pieces of triangle l (which has a map), in the host's
// order (core::PieceStrata): the lanes weigh consecutive cells of the box together, then every
// lane adds the weights of positive ones in cell order, so that each holds the host's running
// sum bit for bit. A lane that `seeks` takes the cell that core::PieceStrata::pick takes for its
// `target`: the first of positive weight whose running sum exceeds the target or reaches `total`.
// Returns the sum over all pieces (the total) when no lane seeks.
// Call with the whole subgroup, l and map subgroup-uniform.
double sweep_pieces(PieceLattice l, DensityMap map, uint64_t texels, bool seeks, double target, double total,
                    out uint64_t cell) {
  uvec4 members = subgroupBallot(true);
  bool any_seeks = subgroupAny(seeks);
  uint lane = subgroupBallotExclusiveBitCount(members), width = subgroupBallotBitCount(members);
  uint64_t cells = lattice_columns(l) * uint64_t(l.y1 - l.y0 + 1l);
  double sum = 0.0lf;
  bool found = !seeks;
  cell = 0ul;
  for (uint64_t first = 0ul; first < cells && !(any_seeks && subgroupAll(found)); first += uint64_t(width)) {
    double weight = first + uint64_t(lane) < cells ? piece_weight(l, map, texels, first + uint64_t(lane)) : 0.0lf;
    uvec2 bits = unpackDouble2x32(weight);
    // The chunk's weights in lane order: lane r holds cell first + r.
    uint r = 0u;
    for (uint id = 0u; id < gl_SubgroupSize; ++id) {
      if (!subgroupBallotBitExtract(members, id)) continue;
      double w = packDouble2x32(uvec2(subgroupBroadcast(bits.x, id), subgroupBroadcast(bits.y, id)));
      if (w > 0.0lf) {
        sum += w;
        if (!found && (sum > target || sum >= total)) {
          found = true;
          cell = first + uint64_t(r);
        }
      }
      ++r;
    }
  }
  return sum;
}

#endif
