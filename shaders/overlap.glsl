// Exact triangle/rectangle overlap area: the GPU twin of lightsampler/overlap.h (paper,
// Section 4, Eq. 5), in float, relative to the rectangle's corner.
#ifndef LIGHTSAMPLER_OVERLAP_GLSL
#define LIGHTSAMPLER_OVERLAP_GLSL

float integral_abs_linear(float a, float b, float len) {
  if ((a >= 0.0) == (b >= 0.0)) return len * abs(a + b) * 0.5;
  return len * (a * a + b * b) / (2.0 * abs(a - b));
}

float edge_term(vec2 a, vec2 b, float w, float h) {
  if (a.y == b.y) return 0.0;
  float y_lo = max(min(a.y, b.y), 0.0);
  float y_hi = min(max(a.y, b.y), h);
  if (!(y_lo < y_hi)) return 0.0;
  float dx = b.x - a.x, span = b.y - a.y;
  float x_lo = a.x + dx * ((y_lo - a.y) / span);
  float x_hi = a.x + dx * ((y_hi - a.y) / span);
  float dy = y_hi - y_lo;
  float term = integral_abs_linear(x_lo, x_hi, dy) - integral_abs_linear(x_lo - w, x_hi - w, dy);
  return b.y > a.y ? 0.5 * term : -0.5 * term;
}

// Area of triangle (a, b, c) inside the rectangle [lo, hi].
float rect_triangle_overlap(vec2 a, vec2 b, vec2 c, vec2 lo, vec2 hi) {
  a -= lo;
  b -= lo;
  c -= lo;
  float w = hi.x - lo.x, h = hi.y - lo.y;
  float cross_z = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (cross_z == 0.0) return 0.0;
  float sum = edge_term(a, b, w, h) + edge_term(b, c, w, h) + edge_term(c, a, w, h);
  return max(cross_z > 0.0 ? sum : -sum, 0.0);
}

#endif
