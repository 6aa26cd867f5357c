#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/counting.h"
#include "core/overlap_variants.h"
#include "lightsampler/overlap.h"

namespace lightsampler::core {

namespace {

// Triangles covering more lattice cells than this are split across tasks by rows, so that one
// huge triangle does not serialise the pass.
constexpr std::int64_t kCellsPerTask = 1 << 14;

struct CellRange {
  std::int64_t first, last;
};

/// Lattice cells [first, last] along one axis that the interval [lo, hi] touches. With clamp
/// addressing, cells are clamped to the map: the edge cells stand for everything beyond.
CellRange cell_range(double lo, double hi, std::uint32_t n, Addressing addressing) {
  auto first = std::int64_t(std::floor(lo)), last = std::int64_t(std::floor(hi));
  if (addressing == Addressing::clamp) {
    first = std::clamp<std::int64_t>(first, 0, n - 1);
    last = std::clamp<std::int64_t>(last, 0, n - 1);
  }
  return {first, last};
}

/// The interval a cell covers. With clamp addressing the edge cells extend to cover [lo, hi].
void cell_bounds(std::int64_t i, std::uint32_t n, Addressing addressing, double lo, double hi,
                 double& a, double& b) {
  a = double(i);
  b = double(i + 1);
  if (addressing == Addressing::clamp) {
    if (i == 0) a = std::min(a, lo);
    if (i == std::int64_t(n) - 1) b = std::max(b, hi);
  }
}

/// x extent of the triangle within the horizontal strip [ya, yb].
bool strip_extent(const double x[3], const double y[3], double ya, double yb, double& xmin,
                  double& xmax) {
  xmin = INFINITY;
  xmax = -INFINITY;
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    const double y0 = std::min(y[k], y[j]), y1 = std::max(y[k], y[j]);
    const double lo = std::max(y0, ya), hi = std::min(y1, yb);
    if (lo > hi) continue;
    if (y1 == y0) {  // horizontal edge inside the strip
      xmin = std::min({xmin, x[k], x[j]});
      xmax = std::max({xmax, x[k], x[j]});
      continue;
    }
    // By fraction of the y-span, not slope: dx/dy overflows for a nearly flat edge.
    const double dx = x[j] - x[k], span = y[j] - y[k];
    const double xl = x[k] + dx * ((lo - y[k]) / span), xh = x[k] + dx * ((hi - y[k]) / span);
    xmin = std::min({xmin, xl, xh});
    xmax = std::max({xmax, xl, xh});
  }
  return xmin <= xmax;
}

struct Accumulator {
  double sum = 0;  // sum of density * overlap, texel units squared
  float max = 0;
  void add(const Accumulator& o) {
    sum += o.sum;
    max = std::max(max, o.max);
  }
};

struct TexelSpaceTriangle {
  double x[3], y[3];
  double xmin, xmax, ymin, ymax;
  double edge[3][3];  ///< a x + b y + c >= 0 inside, for each edge

  /// Whether the rectangle lies inside the triangle: its four corners do (the triangle is convex).
  bool contains(double xa, double ya, double xb, double yb) const {
    for (const auto& e : edge) {
      const double lo_x = e[0] >= 0 ? xa : xb, lo_y = e[1] >= 0 ? ya : yb;  // the corner most outside
      if (e[0] * lo_x + e[1] * lo_y + e[2] < 0) return false;
    }
    return true;
  }
};

/// The triangle's overlap with a cell it touches but does not contain, by the chosen formula.
template <Overlap kind>
double boundary_overlap(const TexelSpaceTriangle& t, double xa, double ya, double xb, double yb) {
  if constexpr (kind == Overlap::clipping) {
    return clipped_overlap(t.x, t.y, xa, ya, xb, yb);
  } else if constexpr (kind == Overlap::sdf) {
    return sdf_overlap(t.x, t.y, xa, ya, xb, yb);
  } else {
    const double a[2] = {t.x[0], t.y[0]}, b[2] = {t.x[1], t.y[1]}, c[2] = {t.x[2], t.y[2]};
    return rect_triangle_overlap(a, b, c, xa, ya, xb, yb);
  }
}

template <Overlap kind>
Accumulator integrate_rows(const TexelSpaceTriangle& t, const DensityMap& map, std::int64_t row0,
                           std::int64_t row1) {
  Accumulator acc;
  for (std::int64_t iy = row0; iy <= row1; ++iy) {
    double ya, yb;
    cell_bounds(iy, map.height, map.addressing, t.ymin, t.ymax, ya, yb);
    double sx0, sx1;
    if (!strip_extent(t.x, t.y, ya, yb, sx0, sx1)) continue;
    const CellRange cols = cell_range(sx0, sx1, map.width, map.addressing);
    for (std::int64_t ix = cols.first; ix <= cols.last; ++ix) {
      // A dark cell adds nothing to either (densities are not negative): most of a sparse map's
      // cells need no overlap.
      const float d = cell_density(map, ix, iy);
      if (d == 0.0f) continue;
      double xa, xb;
      cell_bounds(ix, map.width, map.addressing, t.xmin, t.xmax, xa, xb);
      // Interior cells (most cells of a large triangle) overlap fully: no formula needed (Eq. 6
      // gives 1 there too: a unit cell inside has its centre at least 1/2 from every edge).
      const double overlap = t.contains(xa, ya, xb, yb) ? (xb - xa) * (yb - ya)
                                                        : boundary_overlap<kind>(t, xa, ya, xb, yb);
      if (!(overlap > 0)) continue;
      acc.sum += double(d) * overlap;
      acc.max = std::max(acc.max, d);
    }
  }
  return acc;
}

Accumulator integrate_rows(Overlap overlap, const TexelSpaceTriangle& t, const DensityMap& map,
                           std::int64_t row0, std::int64_t row1) {
  switch (overlap) {
    case Overlap::clipping: return integrate_rows<Overlap::clipping>(t, map, row0, row1);
    case Overlap::sdf: return integrate_rows<Overlap::sdf>(t, map, row0, row1);
    case Overlap::closed_form: break;
  }
  return integrate_rows<Overlap::closed_form>(t, map, row0, row1);
}

}  // namespace

TriangleIntegral integrate_triangle(const TriangleRecord& triangle, const TexelTriangle& texel,
                                    std::span<const DensityMap> maps, Overlap overlap) {
  if (triangle.map == kNoMap || !(triangle.area > 0)) return {0.0, 0.0f};
  const DensityMap& map = maps[triangle.map];
  if (texel.edge1[0] == 0 && texel.edge1[1] == 0 && texel.edge2[0] == 0 && texel.edge2[1] == 0) {
    // UV-degenerate: constant density, read where the realization pass reads it.
    const float d = texel_triangle_density(texel, maps, 0, 0);
    return {double(d) * triangle.area, d};
  }
  TexelSpaceTriangle t;
  for (int k = 0; k < 3; ++k) {
    t.x[k] = double(triangle.uv[k][0]) * map.width;
    t.y[k] = double(triangle.uv[k][1]) * map.height;
  }
  t.xmin = std::min({t.x[0], t.x[1], t.x[2]});
  t.xmax = std::max({t.x[0], t.x[1], t.x[2]});
  t.ymin = std::min({t.y[0], t.y[1], t.y[2]});
  t.ymax = std::max({t.y[0], t.y[1], t.y[2]});
  const double cross = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
  const double uv_area = 0.5 * std::abs(cross);
  for (int k = 0; k < 3; ++k) {
    // Left of a counter-clockwise edge is inside; flip for clockwise triangles.
    const int j = (k + 1) % 3;
    const double sign = cross > 0 ? 1 : -1;
    t.edge[k][0] = -sign * (t.y[j] - t.y[k]);
    t.edge[k][1] = sign * (t.x[j] - t.x[k]);
    t.edge[k][2] = -(t.edge[k][0] * t.x[k] + t.edge[k][1] * t.y[k]);
  }
  const CellRange rows = cell_range(t.ymin, t.ymax, map.height, map.addressing);
  const CellRange cols = cell_range(t.xmin, t.xmax, map.width, map.addressing);
  if (rows.first == rows.last && cols.first == cols.last && overlap != Overlap::sdf) {
    // Inside one cell: the overlap is the whole triangle, exactly (Eq. 6 approximates it too).
    const float d = cell_density(map, cols.first, rows.first);
    return {double(d) * triangle.area, d};
  }
  const std::int64_t cells = (rows.last - rows.first + 1) * (cols.last - cols.first + 1);
  Accumulator acc;
  if (cells <= kCellsPerTask) {
    acc = integrate_rows(overlap, t, map, rows.first, rows.last);
  } else {
    const std::int64_t rows_per_task =
        std::max<std::int64_t>(1, kCellsPerTask / (cols.last - cols.first + 1));
    // Deterministic: the sum must not depend on how tasks were scheduled.
    acc = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::int64_t>(rows.first, rows.last + 1, rows_per_task), Accumulator{},
        [&](const tbb::blocked_range<std::int64_t>& r, Accumulator a) {
          a.add(integrate_rows(overlap, t, map, r.begin(), r.end() - 1));
          return a;
        },
        [](Accumulator a, const Accumulator& b) {
          a.add(b);
          return a;
        });
  }
  return {acc.sum * (double(triangle.area) / uv_area), acc.max};
}

namespace {

template <class Selected>
double count_selected(std::span<const TriangleRecord> triangles, std::span<const TexelTriangle> texel_triangles,
                      std::span<const DensityMap> maps, const Selected& selected, Overlap overlap,
                      Buffer<double>& expected_counts, Buffer<float>& max_density) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        if (!selected(triangles[i])) continue;
                        const TriangleIntegral integral =
                            integrate_triangle(triangles[i], texel_triangles[i], maps, overlap);
                        expected_counts[i] = integral.expected;
                        max_density[i] = integral.max_density;
                      }
                    });
  return sum(expected_counts.span());
}

}  // namespace

double count(std::span<const TriangleRecord> triangles,
             std::span<const TexelTriangle> texel_triangles, std::span<const DensityMap> maps,
             Buffer<double>& expected_counts, Buffer<float>& max_density, Overlap overlap) {
  expected_counts.resize(triangles.size());
  max_density.resize(triangles.size());
  return count_selected(triangles, texel_triangles, maps, [](const TriangleRecord&) { return true; },
                        overlap, expected_counts, max_density);
}

double recount(std::span<const TriangleRecord> triangles, std::span<const TexelTriangle> texel_triangles,
               std::span<const DensityMap> maps, std::span<const std::uint8_t> stale,
               Buffer<double>& expected_counts, Buffer<float>& max_density, Overlap overlap) {
  return count_selected(triangles, texel_triangles, maps,
                        [&](const TriangleRecord& t) { return t.map < stale.size() && stale[t.map] != 0; },
                        overlap, expected_counts, max_density);
}

double sum(std::span<const double> values) {
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, values.size(), 4096), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double total) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) total += values[i];
        return total;
      },
      std::plus<>());
}

}  // namespace lightsampler::core
