// Exact triangle/rectangle overlap area: the GPU twin of lightsampler/overlap.h (paper,
// Section 4, Eq. 5), relative to the rectangle's corner. In double, as on the CPU: in float, a
// cell that only touches a triangle gets a rounding-noise overlap of ~1e-7 of the triangle's
// extent, and a triangle whose density lies only in such cells would get an expected count it
// can never realize (its samples would exhaust their tries once the target scales it up).
#ifndef LIGHTSAMPLER_OVERLAP_GLSL
#define LIGHTSAMPLER_OVERLAP_GLSL

double integral_abs_linear(double a, double b, double len) {
  if ((a >= 0.0lf) == (b >= 0.0lf)) return len * abs(a + b) * 0.5lf;
  return len * (a * a + b * b) / (2.0lf * abs(a - b));
}

double edge_term(dvec2 a, dvec2 b, double w, double h) {
  if (a.y == b.y) return 0.0lf;
  double y_lo = max(min(a.y, b.y), 0.0lf);
  double y_hi = min(max(a.y, b.y), h);
  if (!(y_lo < y_hi)) return 0.0lf;
  double dx = b.x - a.x, span = b.y - a.y;
  double x_lo = a.x + dx * ((y_lo - a.y) / span);
  double x_hi = a.x + dx * ((y_hi - a.y) / span);
  double dy = y_hi - y_lo;
  double term = integral_abs_linear(x_lo, x_hi, dy) - integral_abs_linear(x_lo - w, x_hi - w, dy);
  return b.y > a.y ? 0.5lf * term : -0.5lf * term;
}

// Area of triangle (a, b, c) inside the rectangle [lo, hi].
double rect_triangle_overlap(dvec2 a, dvec2 b, dvec2 c, dvec2 lo, dvec2 hi) {
  a -= lo;
  b -= lo;
  c -= lo;
  double w = hi.x - lo.x, h = hi.y - lo.y;
  double cross_z = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (cross_z == 0.0lf) return 0.0lf;
  double sum = edge_term(a, b, w, h) + edge_term(b, c, w, h) + edge_term(c, a, w, h);
  return max(cross_z > 0.0lf ? sum : -sum, 0.0lf);
}

#endif
