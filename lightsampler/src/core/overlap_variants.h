#pragma once
// The two alternatives to the closed-form overlap (lightsampler/overlap.h) that the paper measures
// it against (Section 6.1, Figures 11 and 12), for Overlap::clipping and Overlap::sdf: polygon
// clipping, exact and slower, and Eq. 6's approximation from the triangle's signed distance at
// the cell's centre, cheaper and biased. The GLSL twins are in shaders/overlap.glsl.

#include <algorithm>
#include <cmath>

#include "core/texel_pieces.h"

namespace lightsampler::core {

/// Area of the triangle (x, y) inside the rectangle [xa, xb] x [ya, yb], by Sutherland–Hodgman
/// clipping against the rectangle's four sides.
inline double clipped_overlap(const double x[3], const double y[3], double xa, double ya, double xb,
                              double yb) {
  // Relative to the rectangle's corner, as the closed form works: small magnitudes.
  BaryPolygon p;
  p.n = 3;
  for (int k = 0; k < 3; ++k) p.v[k] = {x[k] - xa, y[k] - ya};
  const double w = xb - xa, h = yb - ya;
  p = clip(clip(p, 1, 0, 0), -1, 0, w);
  if (p.n < 3) return 0.0;
  p = clip(clip(p, 0, 1, 0), 0, -1, h);
  return p.n < 3 ? 0.0 : p.area();
}

/// Signed distance from (px, py) to the triangle's boundary: positive inside, either orientation.
inline double triangle_sdf(const double x[3], const double y[3], double px, double py) {
  const double cross = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  double nearest = INFINITY;
  bool inside = true;
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    const double ex = x[j] - x[k], ey = y[j] - y[k], wx = px - x[k], wy = py - y[k];
    const double length2 = ex * ex + ey * ey;
    const double t = length2 > 0 ? std::clamp((wx * ex + wy * ey) / length2, 0.0, 1.0) : 0.0;
    const double dx = wx - t * ex, dy = wy - t * ey;
    nearest = std::min(nearest, dx * dx + dy * dy);
    if ((ex * wy - ey * wx) * cross < 0) inside = false;
  }
  return inside ? std::sqrt(nearest) : -std::sqrt(nearest);
}

/// Eq. 6: the fraction of the rectangle inside the triangle taken as clamp(0.5 + SDF(centre), 0,
/// 1), times the rectangle's area (texel units: one for every cell but clamp addressing's edges).
inline double sdf_overlap(const double x[3], const double y[3], double xa, double ya, double xb, double yb) {
  const double inside = 0.5 + triangle_sdf(x, y, 0.5 * (xa + xb), 0.5 * (ya + yb));
  return (xb - xa) * (yb - ya) * std::clamp(inside, 0.0, 1.0);
}

}  // namespace lightsampler::core
