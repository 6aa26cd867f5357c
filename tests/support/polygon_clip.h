#pragma once
// Independent oracle for triangle/rectangle overlap areas: Sutherland–Hodgman clipping of the
// polygon against the rectangle, then the shoelace formula. It shares nothing with the closed form
// of lightsampler/overlap.h except the question, so agreement between the two is evidence for both.
// Everything is in double, header-only.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "lightsampler/mesh.h"

namespace trs_test {

struct Point {
  double x, y;
};
using Polygon = std::vector<Point>;

/// Signed area (positive for counter-clockwise vertex order).
inline double shoelace_area(const Polygon& poly) {
  double twice = 0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Point& p = poly[i];
    const Point& q = poly[(i + 1) % n];
    twice += p.x * q.y - q.x * p.y;
  }
  return 0.5 * twice;
}

namespace detail {

/// Keeps the part of `poly` on the inside of one axis-aligned line: coordinate `axis` (0: x, 1: y)
/// >= bound when keep_above, else <= bound. Crossing points lie exactly on the line.
inline Polygon clip_half_plane(const Polygon& poly, int axis, double bound, bool keep_above) {
  auto coord = [axis](const Point& p) { return axis == 0 ? p.x : p.y; };
  auto inside = [&](const Point& p) { return keep_above ? coord(p) >= bound : coord(p) <= bound; };
  auto crossing = [&](const Point& p, const Point& q) {
    const double t = (bound - coord(p)) / (coord(q) - coord(p));
    return axis == 0 ? Point{bound, p.y + t * (q.y - p.y)} : Point{p.x + t * (q.x - p.x), bound};
  };
  Polygon out;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Point& p = poly[i];
    const Point& q = poly[(i + 1) % n];
    if (inside(p)) {
      out.push_back(p);
      if (!inside(q)) out.push_back(crossing(p, q));
    } else if (inside(q)) {
      out.push_back(crossing(p, q));
    }
  }
  return out;
}

}  // namespace detail

/// The part of `poly` inside [x0, x1] x [y0, y1] (Sutherland–Hodgman; the rectangle is convex, so
/// one pass per side is exact). Degenerate slivers may remain; they have zero area.
inline Polygon clip_to_rectangle(Polygon poly, double x0, double y0, double x1, double y1) {
  poly = detail::clip_half_plane(poly, 0, x0, true);
  poly = detail::clip_half_plane(poly, 0, x1, false);
  poly = detail::clip_half_plane(poly, 1, y0, true);
  return detail::clip_half_plane(poly, 1, y1, false);
}

/// Area of triangle (a, b, c) inside [x0, x1] x [y0, y1], either orientation. The triangle is first
/// moved so that the rectangle's corner is the origin: the shoelace products then stay at the
/// scale of the rectangle, not of the coordinates (texel 4000 would otherwise cost 8 digits).
inline double clipped_triangle_area(Point a, Point b, Point c, double x0, double y0, double x1,
                                    double y1) {
  if (!(x1 > x0) || !(y1 > y0)) return 0;
  const Polygon tri = {{a.x - x0, a.y - y0}, {b.x - x0, b.y - y0}, {c.x - x0, c.y - y0}};
  return std::abs(shoelace_area(clip_to_rectangle(tri, 0, 0, x1 - x0, y1 - y0)));
}

/// Area of a triangle inside one texel of a map.
struct TexelArea {
  std::uint32_t x, y;
  double area;
};

/// The exact area of triangle (a, b, c), given in texel space (u * width, v * height), in every
/// texel of a width x height map it overlaps, ordered by row then column. Parts of the triangle
/// outside the map land where the map's addressing reads them (wrap: modulo the size; clamp: the
/// border texel; mirror: modulo twice the size, the second copy reversed), so the areas always
/// add up to the triangle's area. Texels with zero overlap
/// are left out.
inline std::vector<TexelArea> texel_areas(Point a, Point b, Point c, std::uint32_t width,
                                          std::uint32_t height, lightsampler::Addressing addressing) {
  auto to_map = [addressing](std::int64_t i, std::uint32_t size) {
    const auto n = static_cast<std::int64_t>(size);
    switch (addressing) {
      case lightsampler::Addressing::wrap: return static_cast<std::uint32_t>(((i % n) + n) % n);
      case lightsampler::Addressing::clamp: return static_cast<std::uint32_t>(std::clamp<std::int64_t>(i, 0, n - 1));
      case lightsampler::Addressing::mirror: break;
    }
    const std::int64_t p = ((i % (2 * n)) + 2 * n) % (2 * n);
    return static_cast<std::uint32_t>(p < n ? p : 2 * n - 1 - p);
  };
  const auto lo_x = static_cast<std::int64_t>(std::floor(std::min({a.x, b.x, c.x})));
  const auto hi_x = static_cast<std::int64_t>(std::ceil(std::max({a.x, b.x, c.x})));
  const auto lo_y = static_cast<std::int64_t>(std::floor(std::min({a.y, b.y, c.y})));
  const auto hi_y = static_cast<std::int64_t>(std::ceil(std::max({a.y, b.y, c.y})));
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> by_row;  // key (y, x)
  for (std::int64_t iy = lo_y; iy < hi_y; ++iy) {
    for (std::int64_t ix = lo_x; ix < hi_x; ++ix) {
      const double area = clipped_triangle_area(a, b, c, double(ix), double(iy), double(ix + 1), double(iy + 1));
      if (area > 0) by_row[{to_map(iy, height), to_map(ix, width)}] += area;
    }
  }
  std::vector<TexelArea> out;
  out.reserve(by_row.size());
  for (const auto& [yx, area] : by_row) out.push_back({yx.second, yx.first, area});
  return out;
}

}  // namespace trs_test
