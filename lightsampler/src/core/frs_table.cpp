#include "core/frs_table.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/area_pick.h"
#include "core/texel_pieces.h"

namespace lightsampler::core {
namespace {

using Bary = std::array<double, 2>;

/// A part of a triangle: its corners' barycentrics in the triangle, and how many splits deep.
struct Part {
  std::array<Bary, 3> corners;
  int depth;
};

struct Micro {
  std::array<float, 6> corners;
  float bound;
  double area;      ///< world units squared
  double integral;  ///< of the density over the part
};

Bary texel_point(const TexelTriangle& t, const Bary& b) {
  return {double(t.origin[0]) + b[0] * t.edge1[0] + b[1] * t.edge2[0],
          double(t.origin[1]) + b[0] * t.edge1[1] + b[1] * t.edge2[1]};
}

/// The part as a triangle of texel space, for clipping.
TexelTriangle texel_part(const TexelTriangle& t, const Part& p) {
  const Bary a = texel_point(t, p.corners[0]), b = texel_point(t, p.corners[1]), c = texel_point(t, p.corners[2]);
  return {{float(a[0]), float(a[1])},
          {float(b[0] - a[0]), float(b[1] - a[1])},
          {float(c[0] - a[0]), float(c[1] - a[1])},
          t.map};
}

/// The largest density of any lattice cell the part's bounding box touches, widened by a hair:
/// a point of the part, rounded on its way to a texel, reads no other cell.
float part_bound(const TexelTriangle& t, const DensityMap& map, const Part& p) {
  constexpr double kHair = 1e-3;  // texels
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Bary& corner : p.corners) {
    const Bary q = texel_point(t, corner);
    x0 = std::min(x0, q[0]), x1 = std::max(x1, q[0]);
    y0 = std::min(y0, q[1]), y1 = std::max(y1, q[1]);
  }
  float bound = 0.0f;
  for (auto iy = std::int64_t(std::floor(y0 - kHair)); iy <= std::int64_t(std::floor(y1 + kHair)); ++iy)
    for (auto ix = std::int64_t(std::floor(x0 - kHair)); ix <= std::int64_t(std::floor(x1 + kHair)); ++ix)
      bound = std::max(bound, cell_density(map, ix, iy));
  return bound;
}

Bary midpoint(const Bary& a, const Bary& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}; }

/// A triangle's micro-triangles, by the rule of frs.h.
void subdivide(const TriangleRecord& record, const TexelTriangle& t,
               std::span<const DensityMap> maps, std::vector<Micro>& out) {
  if (t.map == kNoMap || !(record.area > 0.0)) return;
  const DensityMap& map = maps[t.map];
  std::vector<Part> stack = {{{Bary{0.0, 0.0}, Bary{1.0, 0.0}, Bary{0.0, 1.0}}, 0}};
  while (!stack.empty()) {
    const Part p = stack.back();
    stack.pop_back();
    const TexelTriangle part = texel_part(t, p);
    double weighted = 0.0;  // density times the part's own barycentric area (1/2 in all)
    for_each_texel_piece(part, [&](const TexelPiece& piece) {
      weighted += double(cell_density(map, piece.ix, piece.iy)) * piece.area;
    });
    const float bound = part_bound(t, map, p);
    if (!(bound > 0.0f)) continue;
    const double mean = 2.0 * weighted;
    const double texels = 0.5 * std::abs(double(part.edge1[0]) * part.edge2[1] - double(part.edge1[1]) * part.edge2[0]);
    if (mean < kFrsAcceptance * bound && texels > kFrsMinTexels && p.depth < kFrsMaxDepth) {
      const auto& [a, b, c] = p.corners;
      const Bary ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      for (const std::array<Bary, 3>& child : {std::array{a, ab, ca}, std::array{ab, b, bc},
                                               std::array{ca, bc, c}, std::array{ab, bc, ca}})
        stack.push_back({child, p.depth + 1});
      continue;
    }
    const double area = record.area / std::ldexp(1.0, 2 * p.depth);  // a quarter per split
    Micro m{{}, bound, area, area * mean};
    for (int k = 0; k < 3; ++k) {
      m.corners[2 * k] = float(p.corners[k][0]);  // dyadic: exact in float at these depths
      m.corners[2 * k + 1] = float(p.corners[k][1]);
    }
    out.push_back(m);
  }
}

}  // namespace

std::uint64_t FrsTable::bytes() const {
  return parent.size() * (sizeof(std::uint32_t) + sizeof(std::array<float, 6>) + sizeof(float) + sizeof(double)) +
         guide.size() * sizeof(std::uint32_t);
}

FrsTable frs_build(std::span<const TriangleRecord> records,
                   std::span<const TexelTriangle> triangles, std::span<const DensityMap> maps) {
  std::vector<std::vector<Micro>> micro(triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        subdivide(records[i], triangles[i], maps, micro[i]);
                    });
  FrsTable table;
  std::size_t count = 0;
  for (const auto& m : micro) count += m.size();
  table.parent.reserve(count);
  table.corners.reserve(count);
  table.bound.reserve(count);
  table.cdf.resize(count);
  double cumulative = 0.0;
  // In triangle order: the table does not depend on scheduling.
  for (std::size_t i = 0; i < micro.size(); ++i) {
    for (const Micro& m : micro[i]) {
      table.cdf[table.parent.size()] = cumulative += m.area * double(m.bound);
      table.parent.push_back(std::uint32_t(i));
      table.corners.push_back(m.corners);
      table.bound.push_back(m.bound);
      table.expected_total += m.integral;
      table.total_area += m.area;
      table.max_bound = std::max(table.max_bound, m.bound);
    }
  }
  table.guide = area_guide(table.cdf.span());
  return table;
}

}  // namespace lightsampler::core
