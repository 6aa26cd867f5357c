#pragma once
// The GGX (Trowbridge-Reitz) microfacet pieces every glossy lobe of the BSDF is built from, in a
// local frame whose +z is the lobe's normal, and Schlick's Fresnel. Reflection and transmission
// follow Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", with
// Smith's height-correlated masking-shadowing (glTF 2.0, Appendix B) and visible-normal sampling
// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").

#include <algorithm>
#include <cmath>
#include <numbers>
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

/// (1 - |cos|)^5, Schlick's weight of F90.
inline float schlick_weight(float cos_theta) {
  const float m = 1.0f - std::min(std::abs(cos_theta), 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

/// Schlick's Fresnel between `f0` at normal incidence and `f90` at grazing.
inline glm::vec3 schlick(glm::vec3 f0, glm::vec3 f90, float cos_theta) {
  return f0 + (f90 - f0) * schlick_weight(cos_theta);
}
inline float schlick(float f0, float f90, float cos_theta) { return f0 + (f90 - f0) * schlick_weight(cos_theta); }

/// GGX of roughness `alpha` about +z.
struct Ggx {
  float alpha;

  /// D(h), per steradian of microfacet normal; h unit, h.z > 0. The form
  /// (|h_t|^2 / alpha^2 + h_z^2)^2 does not cancel near the peak as 1 + (alpha^2 - 1) cos^2 does
  /// when alpha is small.
  float distribution(glm::vec3 h) const {
    const float a2 = alpha * alpha;
    const float t = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
    return 1.0f / (std::numbers::pi_v<float> * a2 * t * t);
  }
  /// S(cos) = sqrt(alpha^2 + (1 - alpha^2) cos^2): Smith's Lambda = (S / |cos| - 1) / 2. Written with
  /// S, masking stays finite at grazing angles, where Lambda itself diverges.
  float s(float cos_theta) const {
    const float a2 = alpha * alpha;
    return std::sqrt(a2 + (1.0f - a2) * cos_theta * cos_theta);
  }
  /// G1(w): the fraction of the microsurface visible from w.
  float g1(glm::vec3 w) const;
  /// G2(wo, wi) = G1 G1 correlated by height: 1 / (1 + Lambda(wo) + Lambda(wi)).
  float g2(glm::vec3 wo, glm::vec3 wi) const;

  /// A microfacet normal visible from wo (wo.z > 0), drawn with density visible_density().
  glm::vec3 sample_visible(glm::vec3 wo, float u1, float u2) const {
    // Stretch to the alpha = 1 configuration, sample the projected hemisphere, unstretch.
    const glm::vec3 v = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
    const float len2 = v.x * v.x + v.y * v.y;
    const glm::vec3 t1 = len2 > 0.0f ? glm::vec3(-v.y, v.x, 0.0f) / std::sqrt(len2) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 t2 = glm::cross(v, t1);
    const float r = std::sqrt(u1);
    const float phi = 2.0f * std::numbers::pi_v<float> * u2;
    const float p1 = r * std::cos(phi);
    const float half = 0.5f * (1.0f + v.z);
    const float p2 = (1.0f - half) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + half * r * std::sin(phi);
    const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
    return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
  }
  /// G1(wo) max(0, wo.h) D(h) / wo.z: the density of sample_visible(), per steradian of h.
  float visible_density(glm::vec3 wo, glm::vec3 h) const;

  /// D G2 / (4 |wo.z| |wi.z|): a reflection lobe's f for F = 1, written with S so that nothing
  /// divides by a vanishing cosine, G2 = 2 cos_o cos_i / (S_o cos_i + S_i cos_o). wo, wi on the same
  /// side; h their unit half vector.
  float reflection(glm::vec3 wo, glm::vec3 wi, glm::vec3 h) const {
    const float co = std::abs(wo.z), ci = std::abs(wi.z);
    const float denominator = s(wo.z) * ci + s(wi.z) * co;
    return denominator > 0.0f ? distribution(h) / (2.0f * denominator) : 0.0f;
  }
  /// The density, per steradian of wi, of reflecting wo about a visible normal h: D G1(wo) / (4 wo.z),
  /// the visible-normal density over the reflection's Jacobian 4 wo.h.
  float reflection_density(glm::vec3 wo, glm::vec3 h) const { return distribution(h) / (2.0f * (wo.z + s(wo.z))); }
};

/// The direction `wo` (unit, wo.m > 0) takes through an interface of microfacet normal `m`
/// (unit), `eta` being the index on the far side over the index on wo's side; none on total
/// internal reflection.
std::optional<glm::vec3> refract(glm::vec3 wo, glm::vec3 m, float eta);

}  // namespace tracer
