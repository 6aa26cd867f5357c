#pragma once
// The GGX (Trowbridge-Reitz) microfacet pieces every glossy lobe of the BSDF is built from, in a
// local frame whose +z is the lobe's normal, and Schlick's Fresnel. Reflection and transmission
// follow Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", with
// Smith's height-correlated masking-shadowing (glTF 2.0, Appendix B) and visible-normal sampling
// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").

#include <optional>

#include <glm/glm.hpp>

#include "tracer/bsdf.h"  // kMinAlpha

namespace tracer {

/// An orthonormal frame about a unit normal (Duff et al. 2017, "Building an orthonormal basis,
/// revisited"): no branch on the axis, and no loss of precision as the normal nears -z.
struct Frame {
  glm::vec3 tangent, bitangent, normal;

  explicit Frame(glm::vec3 n);
  glm::vec3 to_local(glm::vec3 w) const { return {glm::dot(w, tangent), glm::dot(w, bitangent), glm::dot(w, normal)}; }
  glm::vec3 to_world(glm::vec3 w) const { return w.x * tangent + w.y * bitangent + w.z * normal; }
};

/// Schlick's Fresnel between `f0` at normal incidence and `f90` at grazing.
glm::vec3 schlick(glm::vec3 f0, glm::vec3 f90, float cos_theta);
float schlick(float f0, float f90, float cos_theta);

/// GGX of roughness `alpha` about +z.
struct Ggx {
  float alpha;

  /// D(h), per steradian of microfacet normal; h unit, h.z > 0.
  float distribution(glm::vec3 h) const;
  /// S(cos) = sqrt(alpha^2 + (1 - alpha^2) cos^2): Smith's Lambda = (S / |cos| - 1) / 2. Written with
  /// S, masking stays finite at grazing angles, where Lambda itself diverges.
  float s(float cos_theta) const;
  /// G1(w): the fraction of the microsurface visible from w.
  float g1(glm::vec3 w) const;
  /// G2(wo, wi) = G1 G1 correlated by height: 1 / (1 + Lambda(wo) + Lambda(wi)).
  float g2(glm::vec3 wo, glm::vec3 wi) const;

  /// A microfacet normal visible from wo (wo.z > 0), drawn with density visible_density().
  glm::vec3 sample_visible(glm::vec3 wo, float u1, float u2) const;
  /// G1(wo) max(0, wo.h) D(h) / wo.z: the density of sample_visible(), per steradian of h.
  float visible_density(glm::vec3 wo, glm::vec3 h) const;

  /// D G2 / (4 |wo.z| |wi.z|): a reflection lobe's f for F = 1, written with S so that nothing
  /// divides by a vanishing cosine. wo, wi on the same side.
  float reflection(glm::vec3 wo, glm::vec3 wi) const;
  /// The density, per steradian of wi, of reflecting wo about a visible normal.
  float reflection_density(glm::vec3 wo, glm::vec3 wi) const;
};

/// The direction `wo` (unit, wo.m > 0) takes through an interface of microfacet normal `m`
/// (unit), `eta` being the index on the far side over the index on wo's side; none on total
/// internal reflection.
std::optional<glm::vec3> refract(glm::vec3 wo, glm::vec3 m, float eta);

}  // namespace tracer
