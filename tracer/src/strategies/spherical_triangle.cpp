#include "strategies/spherical_triangle.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tracer {
namespace {

using glm::dvec3;

constexpr double kPi = std::numbers::pi;

/// Angle between unit vectors, accurate near 0 and pi where acos of their dot product is not.
double angle_between(const dvec3& a, const dvec3& b) {
  if (glm::dot(a, b) < 0.0) return kPi - 2.0 * std::asin(std::min(glm::length(a + b) / 2.0, 1.0));
  return 2.0 * std::asin(std::min(glm::length(b - a) / 2.0, 1.0));
}

/// The part of `v` orthogonal to unit `w`, normalised.
dvec3 orthogonal_part(const dvec3& v, const dvec3& w) { return glm::normalize(v - glm::dot(v, w) * w); }

/// The triangle's corners as unit directions from `p`.
std::array<dvec3, 3> directions(const std::array<glm::vec3, 3>& v, const glm::vec3& p) {
  const dvec3 origin(p);
  return {glm::normalize(dvec3(v[0]) - origin), glm::normalize(dvec3(v[1]) - origin),
          glm::normalize(dvec3(v[2]) - origin)};
}

/// Barycentrics of the point where the ray from `p` along `w` meets the triangle's plane
/// (Möller and Trumbore), clamped into the triangle.
lightsampler::Barycentrics hit_barycentrics(const std::array<glm::vec3, 3>& v, const glm::vec3& p,
                                            const dvec3& w) {
  const dvec3 v0(v[0]), e1 = dvec3(v[1]) - v0, e2 = dvec3(v[2]) - v0, s = dvec3(p) - v0;
  const dvec3 s1 = glm::cross(w, e2);
  const double divisor = glm::dot(s1, e1);
  double b1 = std::max(glm::dot(s, s1) / divisor, 0.0);
  double b2 = std::max(glm::dot(w, glm::cross(s, e1)) / divisor, 0.0);
  if (b1 + b2 > 1.0) {
    const double sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  // Rounded separately, the two can sum past one; then 1 - b1 - b2 would be an ulp below zero.
  const float f1 = float(b1);
  return {f1, std::min(float(b2), 1.0f - f1)};
}

}  // namespace

double solid_angle(const std::array<glm::vec3, 3>& v, const glm::vec3& p) {
  const auto [a, b, c] = directions(v, p);
  const double triple = std::abs(glm::dot(a, glm::cross(b, c)));
  return 2.0 * std::atan2(triple, 1.0 + glm::dot(a, b) + glm::dot(a, c) + glm::dot(b, c));
}

lightsampler::Barycentrics sample_spherical_triangle(const std::array<glm::vec3, 3>& v,
                                                     const glm::vec3& p, float u1, float u2) {
  const auto [a, b, c] = directions(v, p);
  // The great circles through each pair of corners, by their normals; the spherical triangle's
  // angles at a, b and c lie between them.
  const dvec3 n_ab = glm::normalize(glm::cross(a, b)), n_bc = glm::normalize(glm::cross(b, c)),
              n_ca = glm::normalize(glm::cross(c, a));
  const double alpha = angle_between(n_ab, -n_ca), beta = angle_between(n_bc, -n_ab),
               gamma = angle_between(n_ca, -n_bc);
  const double area = alpha + beta + gamma - kPi;

  // The sub-triangle a b c' of area u1 * area, c' on the arc from a to c (Arvo's equations).
  const double sub_area = double(u1) * area;
  const double s = std::sin(sub_area - alpha), t = std::cos(sub_area - alpha);
  const double cos_alpha = std::cos(alpha), sin_alpha = std::sin(alpha);
  const double k1 = t - cos_alpha, k2 = s + sin_alpha * glm::dot(a, b);
  const double cos_ac = std::clamp(((k2 * t - k1 * s) * cos_alpha - k2) / ((k2 * s + k1 * t) * sin_alpha), -1.0, 1.0);
  const dvec3 c_sub = cos_ac * a + std::sqrt(1.0 - cos_ac * cos_ac) * orthogonal_part(c, a);

  // A direction on the arc from b to c', its cosine to b uniform (Arvo's second step).
  const double cos_b = 1.0 - double(u2) * (1.0 - glm::dot(c_sub, b));
  const double sin_b = std::sqrt(std::max(0.0, 1.0 - cos_b * cos_b));
  const dvec3 w = cos_b * b + sin_b * orthogonal_part(c_sub, b);
  return hit_barycentrics(v, p, w);
}

}  // namespace tracer
