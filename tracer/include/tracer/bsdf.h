#pragma once
// The glTF 2.0 material as a BSDF: the metallic-roughness model of the core specification's
// Appendix B with the ratified material extensions that change how a surface scatters light:
// KHR_materials_ior, _specular, _transmission, _volume (its refraction; its absorption is the
// integrator's), _clearcoat and _sheen. Directions are unit vectors in world space pointing away
// from the surface.

#include <optional>

#include <glm/glm.hpp>

#include "tracer/albedo_tables.h"

namespace tracer {

/// Smallest GGX alpha. Without a delta lobe, eval() and pdf() of a glossy lobe are non-zero
/// around its peak (about 1 / (4 pi alpha^2) per steradian, finite in float), so light samples
/// can always be weighted by MIS against BSDF samples. A thin transmissive surface smoother than
/// this (roughness^2 < kMinAlpha) lets light straight through instead (BsdfSample::pass_through).
inline constexpr float kMinAlpha = 1e-3f;

/// The material as read at one surface point (textures applied).
struct SurfaceParams {
  glm::vec3 base_color{1.0f};  ///< linear
  float metallic = 0.0f;
  float roughness = 1.0f;      ///< perceptual; GGX alpha = roughness^2
  /// KHR_materials_specular: the dielectric specular layer's weight (0 leaves a dielectric
  /// Lambertian) and the colour its reflectance at normal incidence is tinted by.
  float specular = 1.0f;
  glm::vec3 specular_color{1.0f};
  /// KHR_materials_ior. 0 is the specification's special value: Fresnel 1 in every direction.
  float ior = 1.5f;
  /// KHR_materials_transmission: the share of the light entering the surface that goes through
  /// it rather than scattering diffusely.
  float transmission = 0.0f;
  /// Without KHR_materials_volume (or with its thickness 0) a transmissive surface is thin: light
  /// goes through without bending. A volume's boundary refracts at `ior`.
  bool thin_walled = true;
  /// KHR_materials_clearcoat: the coat's weight, its roughness, and its unit normal on the side
  /// of the shading normal (the shading normal where zero).
  float clearcoat = 0.0f;
  float clearcoat_roughness = 0.0f;
  glm::vec3 clearcoat_normal{0.0f};
  /// KHR_materials_sheen: the sheen's colour (black: none) and roughness.
  glm::vec3 sheen_color{0.0f};
  float sheen_roughness = 0.0f;
};

struct BsdfSample {
  glm::vec3 wi;      ///< sampled incident direction
  glm::vec3 weight;  ///< f(wo, wi) |cos(n, wi)| / pdf
  /// Solid-angle density of wi; for a pass-through, the probability of drawing it.
  float pdf;
  /// wi = -wo through a smooth thin surface: the one singular lobe, which eval() and pdf() leave
  /// out. The ray goes on as if the surface were not there, its throughput times `weight`.
  bool pass_through = false;
};

/// What a smooth thin surface lets straight through along a direction.
struct PassThrough {
  glm::vec3 transmittance;  ///< the pass-through lobe's weight times its probability
  float probability;        ///< with which sample() draws the pass-through
};

class Bsdf {
 public:
  /// `normal` is the unit shading normal on the surface's front side: the outside of a volume.
  /// A thin surface scatters alike on both sides.
  Bsdf(const SurfaceParams& params, glm::vec3 normal);

  /// f(wo, wi) |cos(n, wi)|, wi on either side of the surface; the pass-through excluded.
  glm::vec3 eval(glm::vec3 wo, glm::vec3 wi) const;
  /// Solid-angle density with which sample() returns wi (other than as a pass-through).
  float pdf(glm::vec3 wo, glm::vec3 wi) const;
  /// Draws wi from three uniforms in [0, 1); none when the draw has no contribution.
  std::optional<BsdfSample> sample(glm::vec3 wo, glm::vec3 u) const;
  /// What the surface lets straight through from -wo to wo; none unless it is thin, smooth and
  /// transmissive.
  std::optional<PassThrough> pass_through(glm::vec3 wo) const;
  /// Whether any light goes through the surface: eval() may be non-zero across it.
  bool transmits() const { return transmission_ > 0.0f; }
  /// Works out now what depends on `wo`, which queries with that wo then only read: several
  /// threads may make them at once (queries with another wo may not).
  void prepare(glm::vec3 wo) const { outgoing(wo); }

 private:
  /// The probabilities with which sample() picks each lobe, as wo sees them: summing to 1 (all 0
  /// where nothing scatters).
  struct Lobes {
    float coat = 0.0f, sheen = 0.0f, specular = 0.0f, transmission = 0.0f, diffuse = 0.0f;
  };
  /// What depends on wo alone, kept for the last wo asked about: every query at a path's vertex
  /// shares one wo. (A Bsdf is therefore not to be queried from two threads at once.)
  struct Outgoing {  // filled in whole by outgoing() before any use
    glm::vec3 wo;
    glm::vec3 o;      ///< wo in the shading frame, mirrored above the surface
    bool front;       ///< wo on the surface's front side
    bool scatters;    ///< wo is neither tangent nor malformed
    Lobes lobes;
    float layer_albedo;  ///< the dielectric layer's albedo at wo, for the diffuse coupling
    float sheen_share;   ///< sheen_share() at wo
    float coat_share;    ///< coat_share() at wo
    glm::vec3 coat_o;    ///< wo in the coat's frame, mirrored above it
  };
  /// eval() and pdf() together: sample() returns exactly what they give for its direction.
  struct Value {
    glm::vec3 f_cos{0.0f};
    float pdf = 0.0f;
  };
  /// The dielectric layer's Fresnel reflectance at cosine `cos_theta` from the microfacet normal,
  /// from the side of index `eta_from` to that of `eta_to` (refraction: total internal
  /// reflection and the cosine on the dense side, as KHR_materials_volume defines them).
  glm::vec3 dielectric_fresnel(float cos_theta, float eta_from, float eta_to) const;
  /// The dielectric layer's directional albedo at cosine `mu` (E(mu) of its largest channel): what
  /// the diffuse under it loses, in the coupling that keeps their sum at most 1.
  float dielectric_albedo(float mu) const;
  /// The share left to the layers under the clearcoat and the sheen, seen at cosines of the
  /// coat's normal and of the shading normal.
  float coat_share(float mu_coat) const;
  float sheen_share(float mu) const;
  /// The lobes as wo sees them: `mu` its cosine to the shading normal, `mu_coat` to the coat's,
  /// from the front (outside) or not.
  Lobes lobes(float mu, float mu_coat, bool front) const;
  const Outgoing& outgoing(glm::vec3 wo) const;
  Value evaluate(glm::vec3 wo, glm::vec3 wi) const;
  /// The front and back indices as wo sees them: (1, ior) from the front of a volume, (ior, 1)
  /// from inside; 1 and 1 for a thin surface.
  glm::vec2 indices(bool wo_in_front) const;

  glm::vec3 base_color_;
  float metallic_, roughness_, alpha_;
  glm::vec3 f0_;  ///< the dielectric layer's reflectance at normal incidence (KHR_materials_specular)
  float f90_;     ///< and at grazing: the specular weight
  float diffuse_remaining_;  ///< 1 - the layer's cosine-weighted average albedo: the coupling's normaliser
  // The albedo tables at this point's roughnesses (albedo_tables.h).
  AlbedoTables::Row<glm::vec2> ggx_row_, coat_row_;
  AlbedoTables::Row<float> sheen_row_;
  mutable Outgoing outgoing_;
  mutable bool has_outgoing_ = false;
  float ior_;
  float transmission_;
  bool thin_walled_;
  bool smooth_;  ///< alpha below kMinAlpha: a thin transmissive surface passes light straight through
  float clearcoat_, clearcoat_roughness_, clearcoat_alpha_;
  glm::vec3 sheen_color_;
  float sheen_roughness_, sheen_max_;
  glm::vec3 tangent_, bitangent_, normal_;  ///< the shading normal's frame
  glm::vec3 coat_tangent_, coat_bitangent_, coat_normal_;
};

}  // namespace tracer
