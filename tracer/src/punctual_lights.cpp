#include "tracer/punctual_lights.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "luminance.h"

namespace tracer {

PunctualLights::PunctualLights(const std::vector<PunctualLight>& lights, float scene_radius)
    : lights_(lights), scene_radius_(scene_radius) {}

float PunctualLights::spot_falloff(const PunctualLight& light, float cos_theta) {
  if (light.kind != PunctualLight::Kind::spot) return 1.0f;
  const float t = std::clamp((cos_theta - light.cos_outer) / (light.cos_inner - light.cos_outer), 0.0f, 1.0f);
  return t * t;
}

float PunctualLights::range_window(const PunctualLight& light, float distance) {
  if (!(light.range > 0.0f)) return 1.0f;
  const float r = distance / light.range;
  return std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
}

double PunctualLights::power(std::uint32_t i) const {
  const PunctualLight& light = lights_[i];
  const double y = luminance(light.intensity);
  constexpr double pi = std::numbers::pi;
  switch (light.kind) {
    case PunctualLight::Kind::point: return 4.0 * pi * y;
    case PunctualLight::Kind::spot: {
      // 2 pi times the integral of the falloff over cos theta: 1 - cos_inner inside, a third of
      // the ramp's width over the squared ramp.
      const double ci = light.cos_inner, co = light.cos_outer;
      return 2.0 * pi * y * ((1.0 - ci) + (ci - co) / 3.0);
    }
    case PunctualLight::Kind::directional:
      return pi * double(scene_radius_) * double(scene_radius_) * y;
  }
  return 0.0;
}

PunctualLi PunctualLights::li(std::uint32_t i, const glm::vec3& p) const {
  const PunctualLight& light = lights_[i];
  PunctualLi out;
  if (light.kind == PunctualLight::Kind::directional) {
    out.wi = -light.direction;
    out.distance = std::numeric_limits<float>::infinity();
    out.li = light.intensity;
    return out;
  }
  const glm::vec3 to_light = light.position - p;
  const float d2 = glm::dot(to_light, to_light);
  if (!(d2 > 0.0f)) return out;
  out.distance = std::sqrt(d2);
  out.wi = to_light / out.distance;
  const float falloff = spot_falloff(light, glm::dot(-out.wi, light.direction)) * range_window(light, out.distance);
  out.li = light.intensity * (falloff / d2);
  return out;
}

float bounding_radius(const std::vector<glm::vec3>& positions) {
  if (positions.empty()) return 0.0f;
  glm::vec3 lower(std::numeric_limits<float>::infinity()), upper(-std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : positions) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  return 0.5f * glm::length(upper - lower);
}

}  // namespace tracer
