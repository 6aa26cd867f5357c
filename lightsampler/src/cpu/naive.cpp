// Naive triangle stratification, the baseline of the paper's Section 6: triangles as strata like
// TRS, but each triangle walks its texels one by one with a polygon clipper, and draws its
// samples texel piece by texel piece instead of by rejection. Exact, and as slow as a triangle's
// texel count.

#include <algorithm>
#include <atomic>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/counting.h"
#include "core/piece_draw.h"
#include "cpu/passes.h"

namespace lightsampler::cpu {
namespace {

/// Density of a piece's texel; zero for a triangle without a map.
float piece_density(const core::TexelTriangle& t, std::span<const core::DensityMap> maps,
                    const core::TexelPiece& piece) {
  return t.map == kNoMap ? 0.0f : core::cell_density(maps[t.map], piece.ix, piece.iy);
}

}  // namespace

double naive_count(std::span<const core::TriangleRecord> records,
                   std::span<const core::TexelTriangle> triangles,
                   std::span<const core::DensityMap> maps, Buffer<double>& expected_counts,
                   Buffer<float>& max_density) {
  const std::size_t n = triangles.size();
  expected_counts.resize(n);
  max_density.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      double integral = 0.0;  // of the density over barycentric area
      float bound = 0.0f;
      core::for_each_texel_piece(triangles[i], [&](const core::TexelPiece& piece) {
        const float d = piece_density(triangles[i], maps, piece);
        integral += double(d) * piece.area;
        bound = std::max(bound, d);
      });
      // Barycentric area 1/2 is the triangle's world area.
      expected_counts[i] = 2.0 * integral * records[i].area;
      max_density[i] = bound;
    }
  });
  return core::sum(expected_counts.span());  // in an order that does not depend on scheduling
}

RealizationResult naive_realize(std::span<const core::TexelTriangle> triangles,
                                std::span<const core::DensityMap> maps,
                                std::span<const std::uint64_t> cdf,
                                std::span<const std::uint32_t> inverse_permutation, PhiloxKey key,
                                std::uint32_t max_tries, Buffer<Sample>& samples) {
  samples.resize(cdf.empty() ? 0 : cdf.back());
  std::atomic<std::uint64_t> candidates{0}, exhausted{0};
  // One triangle a task: their texel counts, and so their costs, differ by orders of magnitude.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cdf.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
    core::PieceStrata strata;
    std::uint64_t tried = 0, gave_up = 0;
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      const std::uint64_t first = p == 0 ? 0 : cdf[p - 1];
      if (cdf[p] == first) continue;
      const std::uint32_t tri = inverse_permutation[p];
      strata.build(triangles[tri], maps);
      for (std::uint64_t k = 0; k < cdf[p] - first; ++k) {
        const core::PieceDraw d = core::draw_from_pieces(strata, tri, triangles[tri], k, key, max_tries);
        tried += d.attempts;
        gave_up += d.landed ? 0 : 1;
        samples[first + k] = d.sample;
      }
    }
    candidates.fetch_add(tried, std::memory_order_relaxed);
    exhausted.fetch_add(gave_up, std::memory_order_relaxed);
  });
  return {candidates.load(), exhausted.load(), 0};
}

}  // namespace lightsampler::cpu
