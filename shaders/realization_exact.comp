#version 460
#extension GL_GOOGLE_include_directive : require
// TRS's exact draws (cpu::realize): the segments whose rejection walk stopped, listed by
// realization.comp, each drawn by one subgroup from its triangle's texel pieces, slots filled
// on. The same samples as the CPU backend's, whatever the order of the list.
#include "workgroup.glsl"
#include "piece_draw.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizationPush p; };

// The triangle whose segment is being drawn.
uint walked_triangle;
TexelTriangle walked_texels;
DensityMap walked_map;

// Slots filled .. slots - 1 of segment `segment` of the walked triangle, drawn exactly
// (cpu::realize): the subgroup's lanes take one slot each, round after round, and walk the
// triangle's pieces together for each attempt's piece (sweep_pieces), so that every lane finds
// the piece the host finds. Call with the whole subgroup, the arguments subgroup-uniform.
void draw_exactly(uint64_t segment, uint64_t first, uint filled, uint slots, inout WalkTally tally) {
  uint lane = subgroupExclusiveAdd(1u);
  uint width = subgroupAdd(1u);
  PieceLattice l = piece_lattice(walked_texels);
  uint64_t unused;
  double total = sweep_pieces(l, walked_map, p.texels, false, 0.0lf, 0.0lf, unused);
  if (total <= 0.0lf) {
    // Counted density that clipping finds in no piece (an overlap of rounding's size): the
    // slots give up, as at max_tries (cpu::realize).
    for (uint slot = filled + lane; slot < slots; slot += width) {
      Samples(p.samples + (first + uint64_t(slot)) * uint64_t(kSampleBytes)).v[0] =
          Sample(walked_triangle, 1.0 / 3.0, 1.0 / 3.0);
      tally.exhausted += 1ul;
    }
    return;
  }
  uvec2 key = uvec2(p.exact_key0, p.exact_key1);
  for (uint round_first = filled; round_first < slots; round_first += width) {
    uint slot = round_first + lane;
    uint64_t k = segment * uint64_t(kSegmentSlots) + uint64_t(slot);
    Sample x = Sample(walked_triangle, 0.0, 0.0);
    bool landed = false;
    uint attempts = 0u;
    // Every lane takes part in each walk; those without a slot or done only look on.
    while (subgroupAny(slot < slots && !landed && attempts < p.max_tries)) {
      bool seeks = slot < slots && !landed && attempts < p.max_tries;
      PieceWords w = piece_words(walked_triangle, k, attempts, key);
      uint64_t j;
      sweep_pieces(l, walked_map, p.texels, seeks, piece_target(w, total), total, j);
      if (seeks) {
        int64_t ix = l.x0 + int64_t(j % lattice_columns(l)), iy = l.y0 + int64_t(j / lattice_columns(l));
        x = point_in_piece(walked_triangle, walked_texels, lattice_piece(l, ix, iy), ix, iy, w, landed);
        ++attempts;
      }
    }
    if (slot < slots) {
      Samples(p.samples + (first + uint64_t(slot)) * uint64_t(kSampleBytes)).v[0] = x;
      tally.candidates += uint64_t(attempts);
      tally.exhausted += landed ? 0ul : 1ul;
      tally.exact += 1ul;
    }
  }
}

void main() {
  Uints list = Uints(p.stopped);
  uint count = min(list.v[0], list.v[1]);
  uint stride = gl_NumWorkGroups.x * gl_NumSubgroups;
  WalkTally tally = WalkTally(0ul, 0ul, 0ul);
  // Every bound below is subgroup-uniform: the subgroup draws together.
  for (uint r = gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID; r < count; r += stride) {
    uint at = kStoppedHeaderUints + r * kStoppedRecordUints;
    uint position = list.v[at], filled = list.v[at + 1u];
    uint64_t segment = packUint2x32(uvec2(list.v[at + 2u], list.v[at + 3u]));
    uint64_t start = position > 0u ? cdf_at(p.cdf, position - 1u) : 0ul, end = cdf_at(p.cdf, position);
    uint64_t first = start + segment * uint64_t(kSegmentSlots);
    uint slots = uint(min(uint64_t(kSegmentSlots), end - first));
    walked_triangle = Uints(p.inverse).v[position];
    walked_texels = Triangles(p.triangles).v[walked_triangle];
    walked_map = Maps(p.maps).v[walked_texels.map];
    draw_exactly(segment, first, filled, slots, tally);
  }
  count_tries(Totals(p.totals), tally);
}
