#include "microfacet.h"

namespace tracer {

Frame::Frame(glm::vec3 n) : normal(n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  tangent = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  bitangent = {b, sign + n.y * n.y * a, -n.y};
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

float Ggx::visible_density(glm::vec3 wo, glm::vec3 h) const {
  // G1(wo) / wo.z = 2 / (wo.z + S(wo)).
  const float oh = glm::dot(wo, h);
  if (!(oh > 0.0f) || !(h.z > 0.0f)) return 0.0f;
  return 2.0f * oh * distribution(h) / (wo.z + s(wo.z));
}

std::optional<glm::vec3> refract(glm::vec3 wo, glm::vec3 m, float eta) {
  const float cos_o = glm::dot(wo, m);
  const float sin2_t = std::max(0.0f, 1.0f - cos_o * cos_o) / (eta * eta);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  return glm::normalize(-wo / eta + (cos_o / eta - cos_t) * m);
}

}  // namespace tracer
