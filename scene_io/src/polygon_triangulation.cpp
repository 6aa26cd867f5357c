#include "scene_io/polygon_triangulation.h"

#include <cmath>
#include <list>

namespace trs {
namespace {

struct Point2 {
  double x, y;
};

double cross(Point2 a, Point2 b, Point2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// The corners projected onto the coordinate plane most parallel to the polygon: dropping the
/// axis along which the Newell normal is largest keeps the projection non-degenerate.
std::vector<Point2> project(std::span<const lightsampler::Float3> corners) {
  double nx = 0, ny = 0, nz = 0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const auto& a = corners[i];
    const auto& b = corners[(i + 1) % corners.size()];
    nx += (double(a.y) - b.y) * (double(a.z) + b.z);
    ny += (double(a.z) - b.z) * (double(a.x) + b.x);
    nz += (double(a.x) - b.x) * (double(a.y) + b.y);
  }
  const double ax = std::abs(nx), ay = std::abs(ny), az = std::abs(nz);
  std::vector<Point2> points;
  points.reserve(corners.size());
  for (const auto& c : corners) {
    if (az >= ax && az >= ay) {
      points.push_back({c.x, c.y});
    } else if (ay >= ax) {
      points.push_back({c.z, c.x});
    } else {
      points.push_back({c.y, c.z});
    }
  }
  return points;
}

double signed_area2(const std::vector<Point2>& points) {
  double sum = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point2 a = points[i], b = points[(i + 1) % points.size()];
    sum += a.x * b.y - b.x * a.y;
  }
  return sum;
}

/// Whether p lies in triangle (a, b, c) of orientation `sign`, boundary included: a vertex on an
/// ear's edge would make the ear overlap what is left of the polygon.
bool in_triangle(Point2 p, Point2 a, Point2 b, Point2 c, double sign) {
  return sign * cross(a, b, p) >= 0 && sign * cross(b, c, p) >= 0 && sign * cross(c, a, p) >= 0;
}

}  // namespace

std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(
    std::span<const lightsampler::Float3> corners) {
  const auto n = static_cast<std::uint32_t>(corners.size());
  std::vector<std::array<std::uint32_t, 3>> triangles;
  if (n < 3) return triangles;
  triangles.reserve(n - 2);

  const std::vector<Point2> points = project(corners);
  const double area = signed_area2(points);
  std::list<std::uint32_t> remaining;
  for (std::uint32_t i = 0; i < n; ++i) remaining.push_back(i);

  if (area != 0) {
    const double sign = area > 0 ? 1.0 : -1.0;
    while (remaining.size() > 3) {
      bool clipped = false;
      for (auto it = remaining.begin(); it != remaining.end(); ++it) {
        const auto prev = it == remaining.begin() ? std::prev(remaining.end()) : std::prev(it);
        const auto next = std::next(it) == remaining.end() ? remaining.begin() : std::next(it);
        const Point2 a = points[*prev], b = points[*it], c = points[*next];
        if (sign * cross(a, b, c) <= 0) continue;  // reflex or flat corner: not an ear
        bool empty = true;
        for (const std::uint32_t other : remaining) {
          if (other == *prev || other == *it || other == *next) continue;
          if (in_triangle(points[other], a, b, c, sign)) {
            empty = false;
            break;
          }
        }
        if (!empty) continue;
        triangles.push_back({*prev, *it, *next});
        remaining.erase(it);
        clipped = true;
        break;
      }
      if (!clipped) break;
    }
  }
  // Three corners left, or a polygon with no clippable ear (zero area, self-intersecting): fan.
  const std::vector<std::uint32_t> rest(remaining.begin(), remaining.end());
  for (std::size_t i = 1; i + 1 < rest.size(); ++i)
    triangles.push_back({rest[0], rest[i], rest[i + 1]});
  return triangles;
}

}  // namespace trs
