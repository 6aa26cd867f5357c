#pragma once
// A light of the scene, whatever its kind (pbrt-v4's Light): an emissive triangle or a punctual
// light (point, spot, directional). Each answers its power, by which the light choices weigh
// lights against each other, and what it brings to a shading point: a light sample in solid
// angle, and the solid-angle density of a point on it that a BSDF sample found. Where on a
// triangle the point lies is the strategy's to draw (a point on the triangle its choice picked,
// or one of trs's point lights); the light turns that point into what the shading point sees.

#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

namespace tracer {

class Emitters;

/// Where lights are seen from: a shading point. Every light sample is seen from one
/// (LightLiSample); strategies that weigh lights by distance and orientation (the light tree)
/// also choose by it.
struct ShadingPoint {
  glm::vec3 position;
  glm::vec3 normal;  ///< unit shading normal
};

/// A point on an emissive triangle, with what a connection to it reads: `trs` writes one per
/// point light every pass (its light records), so that a connection reads one aligned 64-byte
/// line and looks up no texture. Seen from a shading point it is a LightLiSample (seen_from()).
struct alignas(64) LightPoint {
  glm::vec3 position;
  /// Area density (per world area) the estimator divides by.
  float pdf;
  glm::vec3 normal;  ///< unit geometric normal of the light's front face
  /// Area density at this point as pdf() gives it, for MIS weights. Equal to `pdf` except for
  /// point-light sets, whose estimator carries the set's size (see TrsStrategy).
  float mis_pdf;
  glm::vec3 radiance;  ///< emitted towards the front, and towards the back if two_sided
  std::uint32_t light;  ///< the emissive triangle
  float b1;
  float b2;
  bool two_sided;

  /// Radiance leaving the point towards unit direction `w`.
  glm::vec3 radiance_towards(glm::vec3 w) const {
    return two_sided || glm::dot(w, normal) > 0.0f ? radiance : glm::vec3(0.0f);
  }
};
static_assert(sizeof(LightPoint) == 64);

/// A light sample seen from a shading point, in solid angle, whatever the light (pbrt-v4's
/// LightLiSample): what next-event estimation reads. A punctual light's direction is a Dirac
/// delta, which its `li` and `pdf` leave out, as pbrt-v4's do: `li` is the irradiance it brings
/// and `pdf` the probability of having chosen it.
struct LightLiSample {
  glm::vec3 li;        ///< radiance arriving along wi, through a clearcoat over the light
  glm::vec3 wi;        ///< unit, from the shading point towards the light
  float distance;      ///< to the point on the light; infinite for a directional light
  float pdf;           ///< solid-angle density of wi, which the estimate divides by
  float mis_pdf;       ///< solid-angle density pdf() gives wi, for MIS; zero for a punctual light
  glm::vec3 position;  ///< the point on the light; unused for a directional light
  glm::vec3 normal;    ///< the light's geometric normal there; zero for a punctual light
  std::uint32_t light;  ///< an emissive triangle, or Emitters::count() + a punctual light
  float b1 = 0.0f;     ///< where on the triangle
  float b2 = 0.0f;
  bool delta = false;  ///< a punctual light: no BSDF sample finds it

  bool distant() const { return std::isinf(distance); }
};

/// An area density at a light point seen from a shading point, as a solid-angle density.
inline float solid_angle_density(float area_density, float distance, float cos_at_light) {
  const float c = std::abs(cos_at_light);
  return c > 0.0f ? area_density * distance * distance / c : 0.0f;
}

/// Light `index()` of the emitters, numbered as the light choices number them: the emissive
/// triangles, then the punctual lights (Emitters::count() + i). A view: the emitters must outlive
/// it.
class Light {
 public:
  enum class Kind : std::uint8_t { triangle, point, spot, directional };

  Light(const Emitters& emitters, std::uint32_t index) : emitters_(&emitters), index_(index) {}

  std::uint32_t index() const { return index_; }
  Kind kind() const;
  /// A punctual light: the direction to it is a Dirac delta, which no BSDF sample finds.
  bool delta() const { return kind() != Kind::triangle; }

  /// Emitted power, W in luminance (pbrt-v4's Phi): a triangle's pi times its density integral,
  /// twice where it emits from both faces (a Lambertian face of radiance L and area A emits
  /// pi L A); a punctual light's PunctualLights::power. The one measure by which lights are
  /// weighed against each other by power.
  double power() const;

  /// A triangle's point (b1, b2), drawn with area density `pdf` (which the estimate divides by)
  /// and `mis_pdf` (what pdf() gives, for MIS): where it is, which way it faces, and the radiance
  /// it sends, read once.
  LightPoint point(float b1, float b2, float pdf, float mis_pdf) const;
  /// A triangle's `point` seen from `at`: the radiance it sends there through its clearcoat, its
  /// densities in solid angle; none where `at` is on the point itself.
  std::optional<LightLiSample> sample_li(const LightPoint& point, const ShadingPoint& at) const;
  /// A punctual light seen from `at`, chosen with probability `pmf`: a delta sample of the
  /// irradiance it brings; none where it brings nothing.
  std::optional<LightLiSample> sample_li(double pmf, const ShadingPoint& at) const;
  /// A triangle's point drawn with area density `area_density`, seen along unit `wo` (from the
  /// point towards the shading point) `distance` away: its density in solid angle (pbrt-v4's
  /// PDF_Li, where a BSDF sample found the point).
  float pdf_li(float area_density, glm::vec3 wo, float distance) const;

 private:
  const Emitters* emitters_;
  std::uint32_t index_;
};

}  // namespace tracer
