#include "sheen.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tracer {
namespace {

/// The fit of the sheen's Lambda (Conty and Kulla 2017, table 1), interpolated in (1 - alpha)^2.
float fit(float x, float alpha) {
  const float t = (1.0f - alpha) * (1.0f - alpha);
  const float a = std::lerp(21.5473f, 25.3245f, t), b = std::lerp(3.82987f, 3.32435f, t),
              c = std::lerp(0.19823f, 0.16801f, t), d = std::lerp(-1.97760f, -1.27393f, t),
              e = std::lerp(-4.32054f, -4.85967f, t);
  return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

float lambda(float cos_theta, float alpha) {
  const float c = std::abs(cos_theta);
  return c < 0.5f ? std::exp(fit(c, alpha)) : std::exp(2.0f * fit(0.5f, alpha) - fit(1.0f - c, alpha));
}

}  // namespace

// The distribution's exponent 1 / alpha overflows float's range of sin^(1/alpha) near alpha = 0:
// the smallest alpha keeps it a sharp grazing peak rather than a delta.
Sheen::Sheen(float roughness) : alpha(std::max(roughness * roughness, 1e-3f)) {}

float Sheen::reflection(glm::vec3 wo, glm::vec3 wi) const {
  const float half_length = glm::length(wo + wi);
  if (!(half_length > 0.0f)) return 0.0f;
  const float cos_h = (wo.z + wi.z) / half_length;
  const float sin2_h = std::max(0.0f, 1.0f - cos_h * cos_h);
  const float inverse = 1.0f / alpha;
  const float d = (2.0f + inverse) * std::pow(sin2_h, 0.5f * inverse) / (2.0f * std::numbers::pi_v<float>);
  // D / (4 (1 + Lambda_o + Lambda_i) cos_o cos_i) times cos_i.
  return d / (4.0f * (1.0f + lambda(wo.z, alpha) + lambda(wi.z, alpha)) * std::abs(wo.z));
}

}  // namespace tracer
