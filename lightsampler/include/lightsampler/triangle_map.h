#pragma once
// Uniform points on a triangle: Heitz's low-distortion square-to-triangle map ("A Low-Distortion
// Map Between Triangle and Square", 2019). Arithmetic only, no square root.

namespace lightsampler {

/// Barycentric weights of a triangle's second and third vertices.
struct Barycentrics {
  float b1, b2;
};

/// Maps (u0, u1) uniform on [0,1)^2 to a uniform point on the triangle.
inline Barycentrics triangle_map(float u0, float u1) {
  float t0, t1;
  if (u0 < u1) {
    t0 = 0.5f * u0;
    t1 = u1 - t0;
  } else {
    t1 = 0.5f * u1;
    t0 = u0 - t1;
  }
  // b2 = 1 - t0 - t1 = 1 - max(u0, u1), computed exactly: 1 - t0 - t1 in float can round to
  // b1 + b2 > 1, a point just outside the triangle.
  return {t1, 1.0f - (u0 < u1 ? u1 : u0)};
}

}  // namespace lightsampler
