#include "tracer/scene.h"

#include <algorithm>
#include <cmath>

namespace tracer {

glm::vec3 Keyframes::at(double seconds) const {
  const auto after = std::upper_bound(times.begin(), times.end(), float(seconds));
  if (after == times.begin()) return values.front();
  if (after == times.end()) return values.back();
  const std::size_t i = std::size_t(after - times.begin());
  if (step) return values[i - 1];
  const float t = float((seconds - times[i - 1]) / (times[i] - times[i - 1]));
  return values[i - 1] + t * (values[i] - values[i - 1]);
}

namespace {

bool positive(glm::vec3 v) { return v.r > 0.0f || v.g > 0.0f || v.b > 0.0f; }

}  // namespace

bool Material::emissive() const {
  const bool factor = emissive_factor_keys
                          ? std::any_of(emissive_factor_keys->values.begin(), emissive_factor_keys->values.end(), positive)
                          : positive(emissive_factor);
  const bool strength = emissive_strength_keys
                            ? std::any_of(emissive_strength_keys->values.begin(), emissive_strength_keys->values.end(),
                                          [](glm::vec3 v) { return v.x > 0.0f; })
                            : emissive_strength > 0.0f;
  return factor && strength;
}

glm::vec3 Volume::transmittance(float distance) const {
  if (!std::isfinite(attenuation_distance)) return glm::vec3(1.0f);
  return glm::pow(attenuation_color, glm::vec3(distance / attenuation_distance));
}

bool Scene::animated() const {
  return std::any_of(materials.begin(), materials.end(),
                     [&](const Material& m) {
                       return m.emissive() && (m.emission_animated() ||
                                               (m.emissive_texture.present() &&
                                                textures[std::size_t(m.emissive_texture.texture)].frames));
                     });
}

}  // namespace tracer
