#pragma once
// The scene's punctual lights (KHR_lights_punctual) as next-event estimation sees them: each
// gives what it brings to a shading point, as pbrt-v4's Light::SampleLi does for its delta
// lights, and its power, by which the strategies choose between lights.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "tracer/scene.h"

namespace tracer {

/// A punctual light seen from a point.
struct PunctualLi {
  glm::vec3 li{0.0f};  ///< irradiance it brings on a surface facing it (W/m^2, RGB); zero: none
  glm::vec3 wi{0.0f};  ///< unit, towards the light
  float distance = 0.0f;  ///< to the light; infinite for a directional light
};

class PunctualLights {
 public:
  /// `lights` must outlive this. `scene_radius`: of a sphere bounding the scene, which a
  /// directional light's power is taken over (pbrt-v4's DistantLight::Phi).
  PunctualLights(const std::vector<PunctualLight>& lights, float scene_radius);

  std::uint32_t count() const { return std::uint32_t(lights_.size()); }
  const PunctualLight& operator[](std::uint32_t i) const { return lights_[i]; }

  /// Emitted power in luminance (W, Rec.709 Y): 4 pi I for a point light, I over the solid
  /// angle of a spot weighed by its falloff, pi r^2 E for a directional light over the scene.
  double power(std::uint32_t i) const;
  /// What light `i` brings to `p`.
  PunctualLi li(std::uint32_t i, const glm::vec3& p) const;

  /// glTF's spot falloff at cosine `cos_theta` from the axis: 1 inside the inner cone, 0 outside
  /// the outer, the square of a linear ramp in the cosine between (KHR_lights_punctual).
  static float spot_falloff(const PunctualLight& light, float cos_theta);
  /// glTF's window where a range is given: max(min(1 - (d / range)^4, 1), 0); 1 without one.
  static float range_window(const PunctualLight& light, float distance);

 private:
  const std::vector<PunctualLight>& lights_;
  float scene_radius_;
};

/// The radius of a sphere about the bounding box of `positions`' centre that holds them all.
float bounding_radius(const std::vector<glm::vec3>& positions);

}  // namespace tracer
