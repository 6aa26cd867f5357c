// Exact triangle/rectangle overlap area: the GPU twin of lightsampler/overlap.h (paper,
// Section 4, Eq. 5), relative to the rectangle's corner; and the alternatives of
// Overlap::clipping and Overlap::sdf, twins of core/overlap_variants.h. In double, as on the CPU: in float, a
// cell that only touches a triangle gets a rounding-noise overlap of ~1e-7 of the triangle's
// extent, and a triangle whose density lies only in such cells would get an expected count it
// can never realize (its samples would exhaust their tries once the target scales it up).
#ifndef LIGHTSAMPLER_OVERLAP_GLSL
#define LIGHTSAMPLER_OVERLAP_GLSL

#include "texel_pieces.glsl"

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

// Overlap::clipping: the triangle clipped by the rectangle's four sides (Sutherland–Hodgman, the
// clipper of naive stratification), relative to the rectangle's corner.
double clipped_overlap(dvec2 a, dvec2 b, dvec2 c, dvec2 lo, dvec2 hi) {
  BaryPolygon polygon = empty_polygon();
  polygon.v[0] = a - lo;
  polygon.v[1] = b - lo;
  polygon.v[2] = c - lo;
  polygon.n = 3;
  dvec2 size = hi - lo;
  polygon = clip(clip(polygon, 1.0lf, 0.0lf, 0.0lf), -1.0lf, 0.0lf, size.x);
  if (polygon.n < 3) return 0.0lf;
  polygon = clip(clip(polygon, 0.0lf, 1.0lf, 0.0lf), 0.0lf, -1.0lf, size.y);
  return polygon.n < 3 ? 0.0lf : polygon_area(polygon);
}

// Signed distance from p to the triangle's boundary: positive inside, either orientation.
double triangle_sdf(dvec2 v[3], dvec2 p) {
  double cross_z = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
  double nearest = 1.0lf / 0.0lf;
  bool inside = true;
  for (int k = 0; k < 3; ++k) {
    dvec2 e = v[(k + 1) % 3] - v[k], w = p - v[k];
    double length2 = dot(e, e);
    double t = length2 > 0.0lf ? clamp(dot(w, e) / length2, 0.0lf, 1.0lf) : 0.0lf;
    dvec2 d = w - t * e;
    nearest = min(nearest, dot(d, d));
    if ((e.x * w.y - e.y * w.x) * cross_z < 0.0lf) inside = false;
  }
  return inside ? sqrt(nearest) : -sqrt(nearest);
}

// Overlap::sdf, the paper's Eq. 6: clamp(0.5 + SDF(centre), 0, 1) times the rectangle's area.
double sdf_overlap(dvec2 a, dvec2 b, dvec2 c, dvec2 lo, dvec2 hi) {
  dvec2 v[3] = dvec2[3](a, b, c);
  double inside = 0.5lf + triangle_sdf(v, 0.5lf * (lo + hi));
  return (hi.x - lo.x) * (hi.y - lo.y) * clamp(inside, 0.0lf, 1.0lf);
}

// The overlap of a cell the triangle crosses, by the formula the pipeline is specialized with.
double boundary_overlap(dvec2 a, dvec2 b, dvec2 c, dvec2 lo, dvec2 hi) {
  if (kOverlap == kOverlapClipping) return clipped_overlap(a, b, c, lo, hi);
  if (kOverlap == kOverlapSdf) return sdf_overlap(a, b, c, lo, hi);
  return rect_triangle_overlap(a, b, c, lo, hi);
}

#endif
