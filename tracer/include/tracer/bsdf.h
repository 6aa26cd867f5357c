#pragma once
// glTF's metallic-roughness surface: a Lambertian base under a GGX microfacet specular layer,
// blended by metallic. Directions are unit vectors in world space pointing away from the surface.

#include <optional>

#include <glm/glm.hpp>

namespace tracer {

/// The material as read at one surface point (textures applied).
struct SurfaceParams {
  glm::vec3 base_color{1.0f};  ///< linear
  float metallic = 0.0f;
  float roughness = 1.0f;      ///< perceptual; GGX alpha = roughness^2
  /// The dielectric specular layer's weight (KHR_materials_specular's specularFactor): 0 leaves
  /// a dielectric Lambertian, its base colour its albedo.
  float specular = 1.0f;
};

struct BsdfSample {
  glm::vec3 wi;      ///< sampled incident direction
  glm::vec3 weight;  ///< f(wo, wi) |cos(n, wi)| / pdf
  float pdf;         ///< solid-angle density of wi
};

class Bsdf {
 public:
  /// `normal` is the unit shading normal, on the side of `wo` or not: the surface is two-sided.
  Bsdf(const SurfaceParams& params, glm::vec3 normal);

  /// f(wo, wi) |cos(n, wi)|. Zero when wo and wi lie on opposite sides (no transmission).
  glm::vec3 eval(glm::vec3 wo, glm::vec3 wi) const;
  /// Solid-angle density with which sample() returns wi.
  float pdf(glm::vec3 wo, glm::vec3 wi) const;
  /// Draws wi from three uniforms in [0, 1); none when the draw has no contribution.
  std::optional<BsdfSample> sample(glm::vec3 wo, glm::vec3 u) const;

 private:
  /// What depends on wo only: the diffuse albedo left under the specular layer, and the
  /// probability with which sample() picks the specular lobe.
  struct Lobes {
    glm::vec3 diffuse;
    float specular_probability;
  };
  /// eval() and pdf() together: sample() returns exactly what they give for its direction.
  struct Value {
    glm::vec3 f_cos{0.0f};
    float pdf = 0.0f;
  };

  /// The layer's Fresnel reflectance at cosine `cos_theta` from the microfacet normal.
  glm::vec3 fresnel(float cos_theta) const;
  Lobes lobes(float cos_o) const;
  Value evaluate(glm::vec3 wo, glm::vec3 wi) const;
  glm::vec3 to_local(glm::vec3 w) const;

  glm::vec3 diffuse_albedo_;  ///< base_color (1 - metallic), before the specular layer's share
  glm::vec3 f0_;              ///< Fresnel reflectance at normal incidence
  float dielectric_cut_;      ///< (1 - specular) (1 - metallic): the dielectric Fresnel taken off
  float alpha_;               ///< GGX roughness, floored
  glm::vec3 tangent_, bitangent_, normal_;  ///< orthonormal frame; normal_ as given, either side
};

}  // namespace tracer
