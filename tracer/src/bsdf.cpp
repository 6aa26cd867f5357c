// glTF 2.0 metallic-roughness BSDF.
//
// Specular: GGX (Trowbridge-Reitz) with Smith height-correlated masking-shadowing and Schlick
// Fresnel, F0 = mix(0.04, base_color, metallic), the dielectric share weighted by `specular`.
// Diffuse: Lambert with albedo base_color (1 - metallic) (1 - max_c F_c(n.wo)). Weighting by the Fresnel at n.wo rather than at
// the half vector takes from the diffuse the energy the specular layer reflects at grazing wo, which
// the half-vector form does not (a white dielectric of roughness 0.1 would reflect 1.48 at n.wo 0.1);
// the price is that the diffuse term is not reciprocal. Taking the largest channel bounds every
// channel alike. The bound is not exact: the visible normals average a Schlick F that is convex in
// wo.h, so the albedo can exceed 1 by about 0.0013 (white dielectric, roughness 0.3, n.wo 0.6).
//
// Sampling picks a lobe with probability proportional to an albedo estimate (luminance of F(n.wo)
// against the diffuse albedo), then draws the GGX visible normals (Heitz 2018, "Sampling the GGX
// distribution of visible normals") or the cosine. Weight and pdf are those of the mixture (one-sample
// MIS over the lobes), computed by the same code as eval() and pdf().

#include "tracer/bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "luminance.h"

namespace tracer {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
/// glTF's dielectric reflectance at normal incidence (an index of refraction of 1.5).
constexpr float kDielectricF0 = 0.04f;

/// Smallest GGX alpha. Without a delta lobe, eval() and pdf() are non-zero around the mirror
/// direction (peak pdf about 1 / (4 pi alpha^2) per steradian, finite in float), so light samples
/// can always be weighted by MIS against BSDF samples.
constexpr float kMinAlpha = 1e-3f;


float max_component(glm::vec3 c) { return std::max({c.x, c.y, c.z}); }

glm::vec3 schlick_fresnel(glm::vec3 f0, float cos_theta) {
  const float m = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (1.0f - f0) * (m2 * m2 * m);
}

/// GGX D(h) per steradian of microfacet normal, for a unit h in the local frame. The form
/// (|h_t|^2 / alpha^2 + h_z^2)^2 does not cancel near the peak as 1 + (alpha^2 - 1) cos^2 does
/// when alpha is small.
float ggx_distribution(glm::vec3 h, float alpha) {
  const float a2 = alpha * alpha;
  const float t = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
  return 1.0f / (kPi * a2 * t * t);
}

/// S(cos) = sqrt(alpha^2 + (1 - alpha^2) cos^2), so that Smith's Lambda = (S / cos - 1) / 2.
/// Masking written with S stays finite at grazing angles, where Lambda itself diverges.
float smith_s(float cos_theta, float alpha) {
  const float a2 = alpha * alpha;
  return std::sqrt(a2 + (1.0f - a2) * cos_theta * cos_theta);
}

/// A GGX normal visible from wo (local, wo.z > 0), drawn with density G1(wo) max(0, wo.h) D(h) / wo.z
/// (Heitz 2018): stretch to the alpha = 1 configuration, sample the projected hemisphere, unstretch.
glm::vec3 sample_visible_normal(glm::vec3 wo, float alpha, float u1, float u2) {
  const glm::vec3 v = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
  const float len2 = v.x * v.x + v.y * v.y;
  const glm::vec3 t1 = len2 > 0.0f ? glm::vec3(-v.y, v.x, 0.0f) / std::sqrt(len2) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t2 = glm::cross(v, t1);
  const float r = std::sqrt(u1);
  const float phi = 2.0f * kPi * u2;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + v.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}

/// Cosine-weighted direction about +z (Malley's method), density z / pi.
glm::vec3 sample_cosine(float u1, float u2) {
  const float r = std::sqrt(u1);
  const float phi = 2.0f * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1))};
}

}  // namespace

Bsdf::Bsdf(const SurfaceParams& params, glm::vec3 normal) : normal_(normal) {
  // Out-of-range inputs would make 1 - metallic negative or alpha above 1, breaking energy bounds.
  const float metallic = std::clamp(params.metallic, 0.0f, 1.0f);
  const float roughness = std::clamp(params.roughness, 0.0f, 1.0f);
  diffuse_albedo_ = params.base_color * (1.0f - metallic);
  f0_ = glm::mix(glm::vec3(kDielectricF0), params.base_color, metallic);
  dielectric_cut_ = (1.0f - std::clamp(params.specular, 0.0f, 1.0f)) * (1.0f - metallic);
  alpha_ = std::max(roughness * roughness, kMinAlpha);
  // Duff et al. 2017, "Building an orthonormal basis, revisited": no branch on the axis, and no
  // loss of precision as normal.z approaches -1.
  const float sign = std::copysign(1.0f, normal.z);
  const float a = -1.0f / (sign + normal.z);
  const float b = normal.x * normal.y * a;
  tangent_ = {1.0f + sign * normal.x * normal.x * a, sign * b, -sign * normal.x};
  bitangent_ = {b, sign + normal.y * normal.y * a, -normal.y};
}

glm::vec3 Bsdf::to_local(glm::vec3 w) const {
  return {glm::dot(w, tangent_), glm::dot(w, bitangent_), glm::dot(w, normal_)};
}

glm::vec3 Bsdf::fresnel(float cos_theta) const {
  // Schlick's F is linear in F0: the dielectric share of the layer scales its own term.
  return schlick_fresnel(f0_, cos_theta) - dielectric_cut_ * schlick_fresnel(glm::vec3(kDielectricF0), cos_theta);
}

Bsdf::Lobes Bsdf::lobes(float cos_o) const {
  const glm::vec3 fresnel = this->fresnel(cos_o);
  const glm::vec3 diffuse = diffuse_albedo_ * (1.0f - max_component(fresnel));
  const float specular = luminance(fresnel);
  const float total = specular + luminance(diffuse);
  // Both zero only for a black metal seen head-on, where every direction contributes nothing.
  return {diffuse, total > 0.0f ? specular / total : 1.0f};
}

Bsdf::Value Bsdf::evaluate(glm::vec3 wo, glm::vec3 wi) const {
  glm::vec3 o = to_local(wo);
  glm::vec3 i = to_local(wi);
  // Two-sided: mirror both through the tangent plane so that wo is above it. The BSDF is isotropic,
  // so the mirror image has the same value.
  if (o.z < 0.0f) {
    o.z = -o.z;
    i.z = -i.z;
  }
  if (!(o.z > 0.0f) || !(i.z > 0.0f)) return {};
  const float half_length = glm::length(o + i);
  if (!(half_length > 0.0f)) return {};  // both at grazing and opposite: underflow
  const glm::vec3 h = (o + i) / half_length;

  const Lobes lobes = this->lobes(o.z);
  const float d = ggx_distribution(h, alpha_);
  const float s_o = smith_s(o.z, alpha_);
  const float s_i = smith_s(i.z, alpha_);
  // D F G2 / (4 cos_o cos_i) times cos_i, with G2 = 2 cos_o cos_i / (S_o cos_i + S_i cos_o): the
  // cosines cancel, so nothing divides by a vanishing cosine.
  const glm::vec3 specular = fresnel(glm::dot(o, h)) * (d * i.z / (2.0f * (s_o * i.z + s_i * o.z)));
  const glm::vec3 diffuse = lobes.diffuse * (i.z / kPi);
  // Visible-normal density G1(wo) D(h) / (4 cos_o) with G1 = 2 cos_o / (cos_o + S_o), per steradian of wi.
  const float specular_pdf = d / (2.0f * (o.z + s_o));
  const float diffuse_pdf = i.z / kPi;
  return {specular + diffuse, glm::mix(diffuse_pdf, specular_pdf, lobes.specular_probability)};
}

glm::vec3 Bsdf::eval(glm::vec3 wo, glm::vec3 wi) const { return evaluate(wo, wi).f_cos; }

float Bsdf::pdf(glm::vec3 wo, glm::vec3 wi) const { return evaluate(wo, wi).pdf; }

std::optional<BsdfSample> Bsdf::sample(glm::vec3 wo, glm::vec3 u) const {
  glm::vec3 o = to_local(wo);
  const bool flipped = o.z < 0.0f;
  if (flipped) o.z = -o.z;
  if (!(o.z > 0.0f)) return std::nullopt;
  glm::vec3 i;
  if (u.x < lobes(o.z).specular_probability) {
    const glm::vec3 h = sample_visible_normal(o, alpha_, u.y, u.z);
    i = 2.0f * glm::dot(o, h) * h - o;  // may point below the surface: no sample then
  } else {
    i = sample_cosine(u.y, u.z);
  }
  if (flipped) i.z = -i.z;
  const glm::vec3 wi = i.x * tangent_ + i.y * bitangent_ + i.z * normal_;
  // Weight and pdf from the world direction returned, so that they agree with eval() and pdf()
  // for it to the last bit, as MIS against light samples needs.
  const Value value = evaluate(wo, wi);
  if (!(value.pdf > 0.0f)) return std::nullopt;
  return BsdfSample{wi, value.f_cos / value.pdf, value.pdf};
}

}  // namespace tracer
