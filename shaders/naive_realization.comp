#version 460
#extension GL_GOOGLE_include_directive : require
// Naive triangle stratification's realization (cpu::naive_realize): one invocation per slot. The
// slot's triangle draws a texel piece in proportion to density times area (a search in the CDF
// of its pieces that counting wrote, then the piece clipped again) and a uniform point in it; no
// rejection, but a point that rounding puts in another texel than its piece's is drawn again,
// up to max_tries attempts. The same stream and arithmetic as the CPU backend: the same samples.
#include "piece_draw.glsl"
#include "workgroup.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizationPush p; };

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

// Attempt `attempt` at slot k of triangle tri. Returns whether the point lands in its piece.
bool attempt_slot(uint tri, TexelTriangle t, PieceLattice l, uint64_t cdf, uint64_t cells, uint64_t k,
                  uint attempt, out Sample drawn) {
  PieceWords w = piece_words(tri, k, attempt, uvec2(p.key0, p.key1));
  double total = Doubles(cdf + (cells - 1ul) * 8ul).v[0];
  uint64_t j = pick_cell(cdf, cells, total, piece_target(w, total));
  int64_t ix = l.x0 + int64_t(j % lattice_columns(l)), iy = l.y0 + int64_t(j / lattice_columns(l));
  bool landed;
  drawn = point_in_piece(tri, t, lattice_piece(l, ix, iy), ix, iy, w, landed);
  return landed;
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
  count_tries(Totals(p.totals), WalkTally(tries, gave_up, 0ul));
}
