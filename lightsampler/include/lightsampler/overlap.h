#pragma once
// Exact area of the intersection of a triangle with an axis-aligned rectangle, by the paper's
// convolution closed form (Section 4, Eq. 5): the triangle's indicator is a sum of three edge
// step functions; convolving each with the box is a clamp, i.e. a difference of absolute values
// of a linear function, whose integral over the edge's y-span is closed-form. No clipping, no
// branching on the shape of the intersection. The GLSL twin is texel_overlap in
// shaders/overlap.glsl.

#include <algorithm>
#include <cmath>

namespace lightsampler {

namespace detail {

/// Integral over a length L of |f| for f linear from a to b.
template <class Real>
Real integral_abs_linear(Real a, Real b, Real length) {
  if ((a >= 0) == (b >= 0)) return length * std::abs(a + b) * Real(0.5);
  return length * (a * a + b * b) / (Real(2) * std::abs(a - b));
}

/// Signed contribution of the directed edge (xa, ya) -> (xb, yb) to the overlap with the box
/// [0, w] x [0, h]: the integral over y of the box-filtered (clamped) edge step function.
template <class Real>
Real edge_term(Real xa, Real ya, Real xb, Real yb, Real w, Real h) {
  if (ya == yb) return 0;
  const Real y_lo = std::max(std::min(ya, yb), Real(0));
  const Real y_hi = std::min(std::max(ya, yb), h);
  if (!(y_lo < y_hi)) return 0;
  // Interpolate by the fraction of the y-span (in [0, 1]), not by a slope: dx/dy overflows for a
  // nearly flat edge, and 0 * inf would make the whole overlap NaN.
  const Real dx = xb - xa, span = yb - ya;
  const Real x_lo = xa + dx * ((y_lo - ya) / span);
  const Real x_hi = xa + dx * ((y_hi - ya) / span);
  const Real dy = y_hi - y_lo;
  // clamp(t, 0, w) - w/2 = (|t| - |t - w|) / 2, with t the part of [0, w] left of the edge.
  const Real term = integral_abs_linear(x_lo, x_hi, dy) - integral_abs_linear(x_lo - w, x_hi - w, dy);
  return yb > ya ? Real(0.5) * term : Real(-0.5) * term;
}

}  // namespace detail

/// Area of triangle (a, b, c) intersected with the rectangle [x0, x1] x [y0, y1]. Either
/// orientation; zero for a degenerate triangle or an empty rectangle.
template <class Real>
Real rect_triangle_overlap(const Real a[2], const Real b[2], const Real c[2], Real x0, Real y0,
                           Real x1, Real y1) {
  // Work relative to the rectangle's corner: small magnitudes, little cancellation.
  const Real ax = a[0] - x0, ay = a[1] - y0, bx = b[0] - x0, by = b[1] - y0;
  const Real cx = c[0] - x0, cy = c[1] - y0;
  const Real w = x1 - x0, h = y1 - y0;
  if (!(w > 0) || !(h > 0)) return 0;
  const Real cross = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  if (cross == 0) return 0;
  const Real sum = detail::edge_term(ax, ay, bx, by, w, h) + detail::edge_term(bx, by, cx, cy, w, h) +
                   detail::edge_term(cx, cy, ax, ay, w, h);
  // Left of every edge is inside for a counter-clockwise triangle: the sum is +area, else -area.
  return std::max(cross > 0 ? sum : -sum, Real(0));
}

/// Area of triangle (a, b, c) intersected with the unit texel [ix, ix+1] x [iy, iy+1] (texel units).
template <class Real>
Real texel_overlap(const Real a[2], const Real b[2], const Real c[2], Real ix, Real iy) {
  return rect_triangle_overlap(a, b, c, ix, iy, ix + 1, iy + 1);
}

}  // namespace lightsampler
