#version 460
#extension GL_GOOGLE_include_directive : require
// Realization (Algorithm 4) through the candidate stream: each subgroup takes chunks of
// kSegmentSlots samples in turn and walks every segment that starts in its chunk (at most one
// per triangle: core::for_each_segment), so small triangles share a subgroup and large ones
// spread over many. Candidates from Heitz's map, accepted against D_T^max; a walk that stops
// after exact_after rejections in a row leaves the rest of its segment to exact draws from the
// triangle's texel pieces. The same samples as the CPU backend's.
#include "workgroup.glsl"
#include "inverse_cdf.glsl"
#include "piece_draw.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizationPush p; };

// The triangle whose segment is being walked.
uint walked_triangle;
TexelTriangle walked_texels;
DensityMap walked_map;
float walked_bound;

bool draw_candidate(uint64_t segment, uint64_t candidate, out Sample drawn) {
  uvec4 u = philox4x32(candidate_counter(walked_triangle, segment, candidate), uvec2(p.key0, p.key1));
  vec2 b = triangle_map(uniform_float(u.x), uniform_float(u.y));
  vec2 point = texel_space_point(walked_texels, b);
  drawn = Sample(walked_triangle, b.x, b.y);
  return uniform_float(u.z) * walked_bound < point_density(walked_map, p.texels, point.x, point.y);
}

#include "candidate_stream.glsl"

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

// The processing index of the triangle holding sample `sample_index`, searched within the guide
// table's bounds when the frame has one.
uint first_position(uint64_t sample_index) {
  if (p.guide == 0ul) return processing_index(p.cdf, p.triangle_count, sample_index);
  uint b = uint(sample_index / guide_bucket(Totals(p.totals).t.sample_count, p.triangle_count));
  return first_above(p.cdf, sample_index, Uints(p.guide).v[b], Uints(p.guide).v[b + 1u]);
}

void main() {
  Totals totals = Totals(p.totals);
  uint64_t n = totals.t.realized;
  uint64_t chunks = (n + uint64_t(kSegmentSlots) - 1ul) / uint64_t(kSegmentSlots);
  uint64_t stride = uint64_t(gl_NumWorkGroups.x) * uint64_t(gl_NumSubgroups);
  WalkTally tally = WalkTally(0ul, 0ul, 0ul);
  // Every bound below is subgroup-uniform: the subgroup walks together.
  for (uint64_t c = uint64_t(gl_WorkGroupID.x) * uint64_t(gl_NumSubgroups) + uint64_t(gl_SubgroupID); c < chunks;
       c += stride) {
    uint64_t lo = c * uint64_t(kSegmentSlots), hi = min(lo + uint64_t(kSegmentSlots), n);
    for (uint position = first_position(lo); position < p.triangle_count; ++position) {
      uint64_t start = position > 0u ? cdf_at(p.cdf, position - 1u) : 0ul, end = cdf_at(p.cdf, position);
      if (start >= hi) break;
      uint64_t segment = start >= lo ? 0ul : (lo - start + uint64_t(kSegmentSlots) - 1ul) / uint64_t(kSegmentSlots);
      uint64_t first = start + segment * uint64_t(kSegmentSlots);
      if (first >= min(hi, end)) continue;
      // N_T > 0, so the triangle has a map and a positive bound.
      walked_triangle = Uints(p.inverse).v[position];
      walked_texels = Triangles(p.triangles).v[walked_triangle];
      walked_map = Maps(p.maps).v[walked_texels.map];
      walked_bound = uintBitsToFloat(Uints(p.max_density).v[walked_triangle]);
      uint slots = uint(min(uint64_t(kSegmentSlots), end - first));
      // The rejection loop's limit (core::TrsTries::rejection), where the device draws exactly.
      PieceLattice l = piece_lattice(walked_texels);
      bool stop = p.exact_after > 0u && lattice_columns(l) * uint64_t(l.y1 - l.y0 + 1l) <= uint64_t(p.exact_cells);
      uint limit = stop ? min(p.max_tries, p.exact_after) : p.max_tries;
      uint filled = walk_segment(p.samples, segment, first, slots, limit, stop, tally);
      if (filled < slots) draw_exactly(segment, first, filled, slots, tally);
    }
  }
  count_tries(totals, tally);
}
