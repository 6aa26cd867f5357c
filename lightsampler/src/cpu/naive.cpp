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
#include "core/texel_pieces.h"
#include "cpu/passes.h"
#include "lightsampler/triangle_map.h"

namespace lightsampler::cpu {
namespace {

/// Density of a piece's texel; zero for a triangle without a map.
float piece_density(const core::TexelTriangle& t, std::span<const core::DensityMap> maps,
                    const core::TexelPiece& piece) {
  return t.map == kNoMap ? 0.0f : core::cell_density(maps[t.map], piece.ix, piece.iy);
}

/// A triangle's pieces of non-zero density and the inclusive CDF of density times area.
struct Strata {
  std::vector<core::TexelPiece> pieces;
  std::vector<double> cdf;

  void build(const core::TexelTriangle& t, std::span<const core::DensityMap> maps) {
    pieces.clear();
    cdf.clear();
    double total = 0.0;
    core::for_each_texel_piece(t, [&](const core::TexelPiece& piece) {
      const double weight = double(piece_density(t, maps, piece)) * piece.area;
      if (weight <= 0.0) return;
      pieces.push_back(piece);
      cdf.push_back(total += weight);
    });
  }
};

/// A uniform point of a convex polygon: a triangle of its fan from vertex 0 by area, then a
/// uniform point of that triangle. `u` uniform in [0, 1) each.
std::array<double, 2> point_in(const core::BaryPolygon& polygon, double area, float u_fan, float u0,
                               float u1) {
  const auto& o = polygon.v[0];
  double target = double(u_fan) * area, below = 0.0;
  int i = 1;
  for (; i < polygon.n - 2; ++i) {
    const auto& a = polygon.v[i];
    const auto& b = polygon.v[i + 1];
    below += 0.5 * std::abs((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]));
    if (target < below) break;
  }
  const auto& a = polygon.v[i];
  const auto& b = polygon.v[i + 1];
  const Barycentrics s = triangle_map(u0, u1);
  return {o[0] + s.b1 * (a[0] - o[0]) + s.b2 * (b[0] - o[0]),
          o[1] + s.b1 * (a[1] - o[1]) + s.b2 * (b[1] - o[1])};
}

/// Whether a sample lies in its triangle and reads the texel of the cell it was drawn in.
bool lands_in(const core::TexelTriangle& t, const Sample& x, std::int64_t ix, std::int64_t iy) {
  if (!(x.b1 >= 0.0f && x.b2 >= 0.0f && x.b1 + x.b2 <= 1.0f)) return false;
  const auto [px, py] = core::texel_space_point(t, x.b1, x.b2);
  return core::floor_to_int(px) == ix && core::floor_to_int(py) == iy;
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
    Strata strata;
    std::uint64_t tried = 0, gave_up = 0;
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      const std::uint64_t first = p == 0 ? 0 : cdf[p - 1];
      if (cdf[p] == first) continue;
      const std::uint32_t tri = inverse_permutation[p];
      const core::TexelTriangle& t = triangles[tri];
      strata.build(t, maps);
      for (std::uint64_t k = 0; k < cdf[p] - first; ++k) {
        Sample x{};
        std::uint32_t attempt = 0;
        for (;; ++attempt) {
          // Two draws of four words per attempt; bit 31 of the last word tells them apart
          // (max_tries stays below 2^31).
          const PhiloxCounter c{tri, std::uint32_t(k), std::uint32_t(k >> 32), attempt};
          const PhiloxCounter u = philox4x32(c, key);
          const PhiloxCounter v = philox4x32({c[0], c[1], c[2], c[3] | 0x80000000u}, key);
          const double pick = (double(u[0]) + double(u[1]) * 0x1p32) * 0x1p-64 * strata.cdf.back();
          const std::size_t i = std::min<std::size_t>(
              std::upper_bound(strata.cdf.begin(), strata.cdf.end(), pick) - strata.cdf.begin(),
              strata.pieces.size() - 1);
          const core::TexelPiece& piece = strata.pieces[i];
          const auto b = point_in(piece.polygon, piece.area, uniform_float(u[2]), uniform_float(v[0]),
                                  uniform_float(v[1]));
          x = {tri, float(b[0]), float(b[1])};
          if (lands_in(t, x, piece.ix, piece.iy)) break;
          if (attempt + 1 >= max_tries) {
            ++gave_up;
            break;
          }
        }
        tried += attempt + 1;
        samples[first + k] = x;
      }
    }
    candidates.fetch_add(tried, std::memory_order_relaxed);
    exhausted.fetch_add(gave_up, std::memory_order_relaxed);
  });
  return {candidates.load(), exhausted.load()};
}

}  // namespace lightsampler::cpu
