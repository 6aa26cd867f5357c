#pragma once
// Exact draws from a triangle's density: a texel piece (core/texel_pieces.h) in proportion to
// density times area, then a uniform point in it. Naive stratification draws every sample so;
// TRS draws so the rest of a segment whose rejection failed too often in a row (a sliver of
// density). The GLSL twin is shaders/piece_draw.glsl.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/texel_pieces.h"
#include "lightsampler/random.h"
#include "lightsampler/sample.h"
#include "lightsampler/triangle_map.h"

namespace lightsampler::core {

/// A triangle's pieces of non-zero density and the inclusive CDF of density times area, summed
/// row by row as the GPU sums them.
struct PieceStrata {
  std::vector<TexelPiece> pieces;
  std::vector<double> cdf;

  void build(const TexelTriangle& t, std::span<const DensityMap> maps) {
    pieces.clear();
    cdf.clear();
    if (t.map == kNoMap) return;
    const DensityMap& map = maps[t.map];
    double total = 0.0;
    // Dark cells are not clipped: a sliver's triangle has few lit ones.
    const auto lit = [&](std::int64_t ix, std::int64_t iy) { return cell_density(map, ix, iy) > 0.0f; };
    for_each_texel_piece(
        t,
        [&](const TexelPiece& piece) {
          const double weight = double(cell_density(map, piece.ix, piece.iy)) * piece.area;
          if (weight <= 0.0) return;
          pieces.push_back(piece);
          cdf.push_back(total += weight);
        },
        lit);
  }

  /// The piece whose CDF interval holds `target`, a uniform in [0, 1) times the total; the last
  /// piece when rounding puts the target at the total.
  const TexelPiece& pick(double target) const {
    const auto i = std::size_t(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
    return pieces[std::min(i, pieces.size() - 1)];
  }
};

/// A uniform point of a convex polygon: a triangle of its fan from vertex 0 by area, then a
/// uniform point of that triangle. `u` uniform in [0, 1) each.
inline std::array<double, 2> point_in(const BaryPolygon& polygon, double area, float u_fan, float u0, float u1) {
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
  return {o[0] + s.b1 * (a[0] - o[0]) + s.b2 * (b[0] - o[0]), o[1] + s.b1 * (a[1] - o[1]) + s.b2 * (b[1] - o[1])};
}

/// Whether a sample lies in its triangle and reads the texel of the cell it was drawn in.
inline bool lands_in(const TexelTriangle& t, const Sample& x, std::int64_t ix, std::int64_t iy) {
  if (!(x.b1 >= 0.0f && x.b2 >= 0.0f && x.b1 + x.b2 <= 1.0f)) return false;
  const auto [px, py] = texel_space_point(t, x.b1, x.b2);
  return floor_to_int(px) == ix && floor_to_int(py) == iy;
}

struct PieceDraw {
  Sample sample;
  std::uint32_t attempts;
  bool landed;  ///< false: max_tries attempts all rounded out of their piece; the last is kept
};

/// Slot k of triangle `tri` drawn from its strata (which hold a piece). Attempt a draws two
/// blocks of four words at counter (tri, k, a), told apart by bit 31 of the last word; it is
/// kept when rounding leaves the point in its piece's texel, else the next attempt draws anew.
inline PieceDraw draw_from_pieces(const PieceStrata& strata, std::uint32_t tri, const TexelTriangle& t,
                                  std::uint64_t k, PhiloxKey key, std::uint32_t max_tries) {
  Sample x{};
  std::uint32_t attempt = 0;
  while (attempt < max_tries) {
    const PhiloxCounter c{tri, std::uint32_t(k), std::uint32_t(k >> 32), attempt++};
    const PhiloxCounter u = philox4x32(c, key);
    const PhiloxCounter v = philox4x32({c[0], c[1], c[2], c[3] | 0x80000000u}, key);
    const double target = (double(u[0]) + double(u[1]) * 0x1p32) * 0x1p-64 * strata.cdf.back();
    const TexelPiece& piece = strata.pick(target);
    const auto b = point_in(piece.polygon, piece.area, uniform_float(u[2]), uniform_float(v[0]), uniform_float(v[1]));
    x = {tri, float(b[0]), float(b[1])};
    if (lands_in(t, x, piece.ix, piece.iy)) return {x, attempt, true};
  }
  return {x, attempt, false};
}

}  // namespace lightsampler::core
