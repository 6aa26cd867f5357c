#include "microfacet.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tracer {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float fifth_power_of_complement(float cos_theta) {
  const float m = 1.0f - std::clamp(std::abs(cos_theta), 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

}  // namespace

Frame::Frame(glm::vec3 n) : normal(n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  tangent = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  bitangent = {b, sign + n.y * n.y * a, -n.y};
}

glm::vec3 schlick(glm::vec3 f0, glm::vec3 f90, float cos_theta) {
  return f0 + (f90 - f0) * fifth_power_of_complement(cos_theta);
}

float schlick(float f0, float f90, float cos_theta) { return f0 + (f90 - f0) * fifth_power_of_complement(cos_theta); }

float Ggx::distribution(glm::vec3 h) const {
  // (|h_t|^2 / alpha^2 + h_z^2)^2 does not cancel near the peak as 1 + (alpha^2 - 1) cos^2 does
  // when alpha is small.
  const float a2 = alpha * alpha;
  const float t = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
  return 1.0f / (kPi * a2 * t * t);
}

float Ggx::s(float cos_theta) const {
  const float a2 = alpha * alpha;
  return std::sqrt(a2 + (1.0f - a2) * cos_theta * cos_theta);
}

float Ggx::g1(glm::vec3 w) const {
  const float c = std::abs(w.z);
  return 2.0f * c / (c + s(w.z));
}

float Ggx::g2(glm::vec3 wo, glm::vec3 wi) const {
  const float co = std::abs(wo.z), ci = std::abs(wi.z);
  const float denominator = s(wo.z) * ci + s(wi.z) * co;
  return denominator > 0.0f ? 2.0f * co * ci / denominator : 0.0f;
}

glm::vec3 Ggx::sample_visible(glm::vec3 wo, float u1, float u2) const {
  // Stretch to the alpha = 1 configuration, sample the projected hemisphere, unstretch.
  const glm::vec3 v = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
  const float len2 = v.x * v.x + v.y * v.y;
  const glm::vec3 t1 = len2 > 0.0f ? glm::vec3(-v.y, v.x, 0.0f) / std::sqrt(len2) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t2 = glm::cross(v, t1);
  const float r = std::sqrt(u1);
  const float phi = 2.0f * kPi * u2;
  const float p1 = r * std::cos(phi);
  const float half = 0.5f * (1.0f + v.z);
  const float p2 = (1.0f - half) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + half * r * std::sin(phi);
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}

float Ggx::visible_density(glm::vec3 wo, glm::vec3 h) const {
  // G1(wo) / wo.z = 2 / (wo.z + S(wo)).
  const float oh = glm::dot(wo, h);
  if (!(oh > 0.0f) || !(h.z > 0.0f)) return 0.0f;
  return 2.0f * oh * distribution(h) / (wo.z + s(wo.z));
}

float Ggx::reflection(glm::vec3 wo, glm::vec3 wi) const {
  const float half_length = glm::length(wo + wi);
  if (!(half_length > 0.0f)) return 0.0f;  // both at grazing and opposite: underflow
  const glm::vec3 h = (wo + wi) / half_length;
  // D G2 / (4 cos_o cos_i) with G2 = 2 cos_o cos_i / (S_o cos_i + S_i cos_o).
  const float co = std::abs(wo.z), ci = std::abs(wi.z);
  const float denominator = s(wo.z) * ci + s(wi.z) * co;
  return denominator > 0.0f ? distribution(h) / (2.0f * denominator) : 0.0f;
}

float Ggx::reflection_density(glm::vec3 wo, glm::vec3 wi) const {
  const float half_length = glm::length(wo + wi);
  if (!(half_length > 0.0f)) return 0.0f;
  const glm::vec3 h = (wo + wi) / half_length;
  // Visible-normal density over the reflection's Jacobian 4 wo.h: D G1(wo) / (4 wo.z).
  return distribution(h) / (2.0f * (wo.z + s(wo.z)));
}

std::optional<glm::vec3> refract(glm::vec3 wo, glm::vec3 m, float eta) {
  const float cos_o = glm::dot(wo, m);
  const float sin2_t = std::max(0.0f, 1.0f - cos_o * cos_o) / (eta * eta);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  return glm::normalize(-wo / eta + (cos_o / eta - cos_t) * m);
}

}  // namespace tracer
