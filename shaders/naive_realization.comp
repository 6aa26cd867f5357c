#version 460
#extension GL_GOOGLE_include_directive : require
// Naive triangle stratification's realization (cpu::naive_realize): one invocation per slot. The
// slot's triangle draws a texel piece in proportion to density times area (a search in the CDF
// of its pieces that counting wrote, then the piece clipped again) and a uniform point in it; no
// rejection, but a point that rounding puts in another texel than its piece's is drawn again,
// up to max_tries attempts. The same stream and arithmetic as the CPU backend: the same samples.
#include "texel_pieces.glsl"
#include "workgroup.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizationPush p; };

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

// The piece cpu/naive.cpp draws for `target`, a uniform in [0, 1) times the total: the first
// cell of the triangle's piece CDF (`cells` > 0 doubles from address `cdf`, ending at `total`)
// whose sum exceeds it, or that reaches the total (rounding can put the target there: the last
// piece of positive weight). A zero-weight cell never rises past the sum before it, so the cell
// found holds a piece.
uint64_t pick_cell(uint64_t cdf, uint64_t cells, double total, double target) {
  uint64_t lo = 0ul, hi = cells - 1ul;
  while (lo < hi) {
    uint64_t mid = lo + (hi - lo) / 2ul;
    double sum = Doubles(cdf + mid * 8ul).v[0];
    if (sum > target || sum >= total) hi = mid; else lo = mid + 1ul;
  }
  return lo;
}

// Attempt `attempt` at slot k of triangle tri: two draws of four words, told apart by bit 31 of
// the last word (max_tries stays below 2^31). Returns whether the point lands in its piece.
bool attempt_slot(uint tri, TexelTriangle t, PieceLattice l, uint64_t cdf, uint64_t cells, uint64_t k,
                  uint attempt, out Sample drawn) {
  uvec4 c = uvec4(tri, uint(k), uint(k >> 32), attempt);
  uvec2 key = uvec2(p.key0, p.key1);
  uvec4 u = philox4x32(c, key), v = philox4x32(uvec4(c.xyz, c.w | 0x80000000u), key);
  double total = Doubles(cdf + (cells - 1ul) * 8ul).v[0];
  precise double target = (double(u.x) + double(u.y) * 4294967296.0lf) * (1.0lf / 18446744073709551616.0lf) * total;
  uint64_t j = pick_cell(cdf, cells, total, target);
  int64_t ix = l.x0 + int64_t(j % lattice_columns(l)), iy = l.y0 + int64_t(j / lattice_columns(l));
  BaryPolygon piece = lattice_piece(l, ix, iy);
  dvec2 b = point_in(piece, polygon_area(piece), uniform_float(u.z), uniform_float(v.x), uniform_float(v.y));
  drawn = Sample(tri, float(b.x), float(b.y));
  return lands_in(t, vec2(drawn.b1, drawn.b2), ix, iy);
}

void main() {
  uint64_t n = Totals(p.totals).t.realized;
  uint64_t tries = 0ul, gave_up = 0ul;
  for (uint64_t slot = thread_index(); slot < n; slot += thread_count()) {
    uint position = processing_index(p.cdf, p.triangle_count, slot);
    uint64_t k = slot - (position > 0u ? cdf_at(p.cdf, position - 1u) : 0ul);
    // N_T > 0, so the triangle has a map and pieces of positive weight.
    uint tri = Uints(p.inverse).v[position];
    TexelTriangle t = Triangles(p.triangles).v[tri];
    uint64_t first = uint64_at(p.piece_offsets, uint64_t(tri)).v[0];
    uint64_t cells = uint64_at(p.piece_offsets, uint64_t(tri) + 1ul).v[0] - first;
    PieceLattice l = piece_lattice(t);
    Sample x = Sample(tri, 0.0, 0.0);
    bool landed = false;
    uint attempts = 0u;
    while (!landed && attempts < p.max_tries) {
      landed = attempt_slot(tri, t, l, p.piece_cdf + first * 8ul, cells, k, attempts, x);
      ++attempts;
    }
    tries += uint64_t(attempts);
    gave_up += landed ? 0ul : 1ul;
    Samples(p.samples + slot * uint64_t(kSampleBytes)).v[0] = x;
  }
  count_tries(Totals(p.totals), tries, gave_up);
}
