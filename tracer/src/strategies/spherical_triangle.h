#pragma once
// A triangle as seen from a point: the solid angle it subtends, and directions drawn uniformly
// within it (Arvo, "Stratified Sampling of Spherical Triangles", SIGGRAPH 1995). Near a large
// light, uniform points by area crowd where it looks small; uniform directions do not.
//
// Computed in double precision: the area of a small spherical triangle is the excess of its
// angles over pi, which single precision would lose to cancellation.

#include <array>

#include <glm/glm.hpp>
#include <lightsampler/triangle_map.h>

namespace tracer {

/// Solid angle, in steradians (0 to 2 pi), of triangle `v` seen from `p` (Van Oosterom and
/// Strackee, 1983). Zero when `p` lies in the triangle's plane outside it.
double solid_angle(const std::array<glm::vec3, 3>& v, const glm::vec3& p);

/// Where a direction from `p`, uniform over the solid angle of triangle `v`, meets the triangle:
/// barycentrics from two uniforms in [0, 1), inside the triangle in single precision
/// (b1 + b2 <= 1 as Emitters::position computes it). `v` must not be seen edge-on from `p`
/// (a solid angle well above zero).
lightsampler::Barycentrics sample_spherical_triangle(const std::array<glm::vec3, 3>& v,
                                                     const glm::vec3& p, float u1, float u2);

}  // namespace tracer
