#include <algorithm>

#include "core/piece_draw.h"
#include "cpu/candidates.h"
#include "cpu/passes.h"

namespace lightsampler::cpu {

namespace {

// Samples per task: many segments, so that the binary search that starts a task is amortised.
constexpr std::size_t kSamplesPerTask = 1 << 14;

}  // namespace

RealizationResult realize(std::span<const core::TexelTriangle> triangles,
                          std::span<const core::DensityMap> maps, std::span<const float> max_density,
                          std::span<const std::uint64_t> cdf,
                          std::span<const std::uint32_t> inverse_permutation, RealizationKeys keys,
                          core::TrsTries tries, Buffer<Sample>& samples) {
  samples.resize(cdf.empty() ? 0 : cdf.back());
  return walk_output(cdf, kSamplesPerTask, [&](const core::SegmentRun& run, WalkTally& tally) {
    const std::uint32_t tri = inverse_permutation[run.position];
    const core::TexelTriangle& t = triangles[tri];
    // N_T > 0, so the triangle has a map and a positive bound.
    const core::DensityMap& map = maps[t.map];
    const float bound = max_density[tri];
    CandidateBatch batch;
    auto judge = [&](std::uint64_t first) {
      draw_candidates(tri, run.segment, first, keys.candidates, batch);
      return accepted_on_triangle(t, map, bound, batch);
    };
    auto lane_sample = [&](int l) { return Sample{tri, batch.b1[l], batch.b2[l]}; };
    Sample* out = samples.data() + run.first;
    const std::uint64_t filled = walk_segment(run, tries.rejection(), out, judge, lane_sample, tally);
    if (filled == run.slots) return;
    // Rejection stopped: the rest of the segment from the triangle's texel pieces.
    core::PieceStrata strata;
    strata.build(t, maps);
    if (strata.pieces.empty()) {
      // Counted density that clipping finds in no piece (an overlap of rounding's size): the
      // slots give up, as at max_tries.
      std::fill(out + filled, out + run.slots, Sample{tri, 1.0f / 3, 1.0f / 3});
      tally.exhausted += run.slots - filled;
      return;
    }
    for (std::uint64_t slot = filled; slot < run.slots; ++slot) {
      const std::uint64_t k = run.segment * core::kSegmentSlots + slot;
      const core::PieceDraw d = core::draw_from_pieces(strata, tri, t, k, keys.exact, tries.max_tries);
      out[slot] = d.sample;
      tally.candidates += d.attempts;
      tally.exhausted += d.landed ? 0 : 1;
    }
    tally.exact += run.slots - filled;
  });
}

}  // namespace lightsampler::cpu
