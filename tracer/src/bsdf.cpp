// The glTF 2.0 material as a BSDF, layered as the specification's graph layers it:
//
//   coated  = clearcoat over (sheen over material)
//   material = mix(dielectric, metal, metallic)
//   metal   = Schlick(f0 = base colour) GGX
//   dielectric = fresnel_mix(layer = GGX reflection,
//                            base = mix(diffuse, base colour times the GGX transmission, transmission))
//
// Each glossy lobe is GGX with Smith's height-correlated masking, its Fresnel Schlick's at the
// microfacet (KHR_materials_specular's f0 and f90; KHR_materials_volume's dense-side cosine and
// total internal reflection). A thin surface's transmission is the reflection lobe mirrored
// through the surface; a volume's boundary refracts (Walter et al. 2007), in radiance units.
//
// Where the specification's informative mixing (1 - F(wo.h)) would reflect more than it receives
// and break reciprocity, the layers are coupled by directional albedo as its Appendix B suggests
// (Kulla and Conty 2017; albedo_tables.h): the diffuse under the dielectric layer weighs
// (1 - E(mu_o)) (1 - E(mu_i)) / (1 - E_avg), which makes an opaque dielectric's albedo exactly its
// layer's E(mu_o) plus the base colour times 1 - E(mu_o); the sheen and the coat take from what lies
// under them min(1 - E(mu_o), 1 - E(mu_i)) (KHR_materials_sheen's albedo scaling, applied to the
// coat too). Every lobe is then reciprocal (refraction up to the squared ratio of indices) and no
// material reflects more than it receives.
//
// A thin, transmissive surface smoother than kMinAlpha lets light straight through: a singular
// lobe (BsdfSample::pass_through), which next-event estimation crosses too (path_tracer.cpp).
//
// Sampling picks a lobe with probability proportional to an estimate of its albedo at wo, then
// draws the GGX visible normals, the cosine (diffuse and sheen) or the pass-through. Weight and pdf
// are those of the mixture (one-sample MIS over the lobes), computed by the same code as eval()
// and pdf().

#include "tracer/bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tracer/albedo_tables.h"
#include "luminance.h"
#include "microfacet.h"
#include "sheen.h"

namespace tracer {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
/// glTF's coat: an index of refraction of 1.5.
constexpr float kCoatF0 = 0.04f;

float max_component(glm::vec3 c) { return std::max({c.x, c.y, c.z}); }

float alpha_of(float roughness) { return std::max(roughness * roughness, kMinAlpha); }

/// Cosine-weighted direction about +z (Malley's method), density z / pi.
glm::vec3 sample_cosine(float u1, float u2) {
  const float r = std::sqrt(u1);
  const float phi = 2.0f * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1))};
}

glm::vec3 reflect(glm::vec3 o, glm::vec3 h) { return 2.0f * glm::dot(o, h) * h - o; }

glm::vec3 mirror(glm::vec3 w) { return {w.x, w.y, -w.z}; }

/// The directional albedo of a GGX lobe of Fresnel f0 + (f90 - f0) (1 - wo.h)^5, its roughness's row
/// of the tables fixed.
float lobe_albedo(const AlbedoTables::Row<glm::vec2>& row, float f0, float f90, float mu) {
  const glm::vec2 e = row.at(mu);
  return f0 * (e.x - e.y) + f90 * e.y;
}

/// A lobe's selection weight: its coefficient (0 where the lobe is absent) times an estimate of its
/// albedo, floored so that a present lobe is always drawn now and then.
float selection(float coefficient, float estimate) { return coefficient * std::max(estimate, 0.01f); }

}  // namespace

Bsdf::Bsdf(const SurfaceParams& params, glm::vec3 normal) {
  // Out-of-range inputs would make 1 - metallic negative or alpha above 1, breaking energy bounds.
  base_color_ = glm::max(params.base_color, glm::vec3(0.0f));
  metallic_ = std::clamp(params.metallic, 0.0f, 1.0f);
  roughness_ = std::clamp(params.roughness, 0.0f, 1.0f);
  alpha_ = alpha_of(roughness_);
  smooth_ = roughness_ * roughness_ < kMinAlpha;
  ior_ = params.ior >= 1.0f ? params.ior : 0.0f;
  const float specular = std::clamp(params.specular, 0.0f, 1.0f);
  const float f0_ior = ior_ == 0.0f ? 1.0f : ((ior_ - 1.0f) / (ior_ + 1.0f)) * ((ior_ - 1.0f) / (ior_ + 1.0f));
  f0_ = glm::min(f0_ior * glm::max(params.specular_color, glm::vec3(0.0f)), glm::vec3(1.0f)) * specular;
  f90_ = specular;
  thin_walled_ = params.thin_walled;
  // What the dielectric layer leaves to the diffuse, averaged over the cosine-weighted hemisphere.
  const AlbedoTables& tables = AlbedoTables::get();
  ggx_row_ = tables.ggx(roughness_);
  const glm::vec2 average = tables.ggx_average(roughness_);
  diffuse_remaining_ = 1.0f - (max_component(f0_) * (average.x - average.y) + f90_ * average.y);
  // A volume of infinite index (ior 0) reflects everything: nothing enters it.
  transmission_ = (thin_walled_ || ior_ > 0.0f) ? std::clamp(params.transmission, 0.0f, 1.0f) * (1.0f - metallic_) : 0.0f;
  clearcoat_ = std::clamp(params.clearcoat, 0.0f, 1.0f);
  clearcoat_roughness_ = std::clamp(params.clearcoat_roughness, 0.0f, 1.0f);
  clearcoat_alpha_ = alpha_of(clearcoat_roughness_);
  sheen_color_ = glm::clamp(params.sheen_color, glm::vec3(0.0f), glm::vec3(1.0f));
  sheen_roughness_ = std::clamp(params.sheen_roughness, 0.0f, 1.0f);
  sheen_max_ = max_component(sheen_color_);
  // The layers' tables and the coat's frame only where there are layers: most surfaces have none.
  if (clearcoat_ > 0.0f) coat_row_ = tables.ggx(clearcoat_roughness_);
  if (sheen_max_ > 0.0f) sheen_row_ = AlbedoTables::sheen(sheen_roughness_);
  const Frame shading(normal);
  tangent_ = shading.tangent;
  bitangent_ = shading.bitangent;
  normal_ = normal;
  const bool own_coat_normal = clearcoat_ > 0.0f && params.clearcoat_normal != glm::vec3(0.0f);
  const Frame coat = own_coat_normal ? Frame(params.clearcoat_normal) : shading;
  coat_tangent_ = coat.tangent;
  coat_bitangent_ = coat.bitangent;
  coat_normal_ = coat.normal;
}

glm::vec2 Bsdf::indices(bool wo_in_front) const {
  if (thin_walled_) return {1.0f, 1.0f};
  return wo_in_front ? glm::vec2(1.0f, ior_) : glm::vec2(ior_, 1.0f);
}

glm::vec3 Bsdf::dielectric_fresnel(float cos_theta, float eta_from, float eta_to) const {
  float c = std::abs(cos_theta);
  if (eta_from > eta_to) {
    // Leaving the dense side: Schlick's approximation holds at the angle on the dense side, which
    // is the transmitted one here; beyond the critical angle everything reflects (F90 unscaled).
    const float ratio = eta_from / eta_to;
    const float sin2_t = ratio * ratio * (1.0f - c * c);
    if (sin2_t >= 1.0f) return glm::vec3(1.0f);
    c = std::sqrt(1.0f - sin2_t);
  }
  return schlick(f0_, glm::vec3(f90_), c);
}

float Bsdf::dielectric_albedo(float mu) const { return lobe_albedo(ggx_row_, max_component(f0_), f90_, mu); }

float Bsdf::coat_share(float mu_coat) const {
  if (clearcoat_ == 0.0f) return 1.0f;
  return 1.0f - clearcoat_ * lobe_albedo(coat_row_, kCoatF0, 1.0f, mu_coat);
}

float Bsdf::sheen_share(float mu) const {
  if (sheen_max_ == 0.0f) return 1.0f;
  return 1.0f - sheen_max_ * sheen_row_.at(mu);
}

Bsdf::Lobes Bsdf::lobes(float mu, float mu_coat, bool front) const {
  // Estimates of each lobe's albedo at wo, which set only how often each is drawn (any positive
  // choice is unbiased): Schlick's Fresnel of the macro normal rather than the tables, where
  // those are not needed for the layers' shares anyway.
  const float coat_albedo = clearcoat_ > 0.0f ? clearcoat_ * lobe_albedo(coat_row_, kCoatF0, 1.0f, mu_coat) : 0.0f;
  const float under_coat = 1.0f - coat_albedo;
  const float sheen_albedo = sheen_max_ > 0.0f ? sheen_max_ * sheen_row_.at(mu) : 0.0f;
  const float base = under_coat * (1.0f - sheen_albedo);
  const float dielectric = 1.0f - metallic_;
  const float colour = luminance(base_color_);
  // Inside a volume, the boundary reflects totally beyond the critical angle whatever the specular
  // weight (F90 unscaled there): its reflection must stay drawable, and its refraction, which then
  // dies, rarely drawn.
  const glm::vec2 eta = indices(front);
  const bool leaving_dense = transmission_ > 0.0f && eta.x > eta.y;
  const glm::vec3 fresnel = dielectric_fresnel(mu, eta.x, eta.y);
  const float layer = max_component(fresnel);
  const float reflected = dielectric * luminance(fresnel) +
                          (metallic_ > 0.0f ? metallic_ * luminance(schlick(base_color_, glm::vec3(1.0f), mu)) : 0.0f);
  const float specular_weight = leaving_dense ? 1.0f : std::max(max_component(f0_), f90_);
  Lobes lobes;
  lobes.coat = selection(clearcoat_, coat_albedo);
  lobes.sheen = selection(under_coat * sheen_max_, sheen_albedo);
  lobes.specular = selection(base * (dielectric * specular_weight + metallic_), reflected);
  lobes.transmission = selection(base * transmission_ * colour, 1.0f - layer);
  lobes.diffuse = selection(base * (dielectric - transmission_) * colour, 1.0f - layer);
  const float total = lobes.coat + lobes.sheen + lobes.specular + lobes.transmission + lobes.diffuse;
  if (!(total > 0.0f)) return {};
  lobes.coat /= total;
  lobes.sheen /= total;
  lobes.specular /= total;
  lobes.transmission /= total;
  lobes.diffuse /= total;
  return lobes;
}

const Bsdf::Outgoing& Bsdf::outgoing(glm::vec3 wo) const {
  if (has_outgoing_ && outgoing_.wo == wo) return outgoing_;
  Outgoing& out = outgoing_;
  out.wo = wo;
  has_outgoing_ = true;
  out.o = {glm::dot(wo, tangent_), glm::dot(wo, bitangent_), glm::dot(wo, normal_)};
  out.scatters = out.o.z != 0.0f && std::isfinite(out.o.z);
  if (!out.scatters) return out;
  // Work with wo above the surface: the lobes are isotropic, so mirroring both directions
  // through the tangent plane changes nothing but the side, which `front` keeps for a volume's
  // indices.
  out.front = out.o.z > 0.0f;
  out.o.z = std::abs(out.o.z);
  out.coat_o = {glm::dot(wo, coat_tangent_), glm::dot(wo, coat_bitangent_), std::abs(glm::dot(wo, coat_normal_))};
  out.lobes = lobes(out.o.z, out.coat_o.z, out.front);
  out.layer_albedo = dielectric_albedo(out.o.z);
  out.sheen_share = sheen_share(out.o.z);
  out.coat_share = coat_share(out.coat_o.z);
  return out;
}

Bsdf::Value Bsdf::evaluate(glm::vec3 wo, glm::vec3 wi) const {
  const Outgoing& out = outgoing(wo);
  if (!out.scatters) return {};
  const glm::vec3& o = out.o;
  glm::vec3 i{glm::dot(wi, tangent_), glm::dot(wi, bitangent_), glm::dot(wi, normal_)};
  if (!out.front) i.z = -i.z;
  const Lobes& lobes = out.lobes;
  const Ggx ggx{alpha_};
  Value value;
  glm::vec3 base(0.0f);  // the material under the sheen and the coat
  glm::vec3 sheen(0.0f);
  if (i.z > 0.0f) {
    const glm::vec3 h = glm::normalize(o + i);
    const float oh = glm::dot(o, h);
    const glm::vec2 eta = indices(out.front);
    const float specular = ggx.reflection(o, i, h) * i.z;
    glm::vec3 fresnel = (1.0f - metallic_) * dielectric_fresnel(oh, eta.x, eta.y);
    if (metallic_ > 0.0f) fresnel += metallic_ * schlick(base_color_, glm::vec3(1.0f), oh);
    base += fresnel * specular;
    const float diffuse_weight = 1.0f - metallic_ - transmission_;
    if (diffuse_weight > 0.0f && diffuse_remaining_ > 1e-4f) {
      const float coupling = (1.0f - out.layer_albedo) * (1.0f - dielectric_albedo(i.z)) / diffuse_remaining_;
      base += diffuse_weight * base_color_ * (coupling * i.z / kPi);
    }
    if (sheen_max_ > 0.0f) sheen = sheen_color_ * Sheen(sheen_roughness_).reflection(o, i);
    value.pdf += lobes.specular * ggx.reflection_density(o, h) + (lobes.diffuse + lobes.sheen) * i.z / kPi;
  } else if (i.z < 0.0f && transmission_ > 0.0f && !(thin_walled_ && smooth_)) {
    const glm::vec3 tint = transmission_ * base_color_;
    if (thin_walled_) {
      const glm::vec3 m = mirror(i);
      const glm::vec3 h = glm::normalize(o + m);
      const float fresnel = max_component(dielectric_fresnel(glm::dot(o, h), 1.0f, 1.0f));
      base += tint * ((1.0f - fresnel) * ggx.reflection(o, m, h) * m.z);
      value.pdf += lobes.transmission * ggx.reflection_density(o, h);
    } else {
      const glm::vec2 eta = indices(out.front);
      const float etap = eta.y / eta.x;  // the index on wi's side over wo's
      glm::vec3 h = glm::normalize(i * etap + o);
      if (h.z < 0.0f) h = -h;
      const float oh = glm::dot(o, h), ih = glm::dot(i, h);
      if (oh > 0.0f && ih < 0.0f) {
        const float denominator = (ih + oh / etap) * (ih + oh / etap);
        const float fresnel = max_component(dielectric_fresnel(oh, eta.x, eta.y));
        // D G2 |i.h| |o.h| / (denominator |o.z| |i.z|) |i.z|, in radiance: over etap^2.
        const float btdf = ggx.distribution(h) * ggx.g2(o, i) * std::abs(ih) * oh / (denominator * o.z * etap * etap);
        base += tint * (1.0f - fresnel) * btdf;
        value.pdf += lobes.transmission * ggx.visible_density(o, h) * std::abs(ih) / denominator;
      }
    }
  }
  const float mu_i = std::abs(i.z);
  glm::vec3 f = sheen_max_ > 0.0f ? sheen + std::min(out.sheen_share, sheen_share(mu_i)) * base : base;
  if (clearcoat_ > 0.0f) {
    const glm::vec3& oc = out.coat_o;
    glm::vec3 ic{glm::dot(wi, coat_tangent_), glm::dot(wi, coat_bitangent_), glm::dot(wi, coat_normal_)};
    if (glm::dot(wo, coat_normal_) < 0.0f) ic.z = -ic.z;
    f *= std::min(out.coat_share, coat_share(std::abs(ic.z)));
    if (oc.z > 0.0f && ic.z > 0.0f) {
      const Ggx coat{clearcoat_alpha_};
      const glm::vec3 h = glm::normalize(oc + ic);
      // The coat's f, times the cosine of wi to the shading normal, as every lobe's.
      f += glm::vec3(clearcoat_ * schlick(kCoatF0, 1.0f, glm::dot(oc, h)) * coat.reflection(oc, ic, h) * mu_i);
      value.pdf += lobes.coat * coat.reflection_density(oc, h);
    }
  }
  value.f_cos = f;
  return value;
}

glm::vec3 Bsdf::eval(glm::vec3 wo, glm::vec3 wi) const { return evaluate(wo, wi).f_cos; }

float Bsdf::pdf(glm::vec3 wo, glm::vec3 wi) const { return evaluate(wo, wi).pdf; }

std::optional<PassThrough> Bsdf::pass_through(glm::vec3 wo) const {
  if (!(thin_walled_ && smooth_ && transmission_ > 0.0f)) return std::nullopt;
  const Outgoing& out = outgoing(wo);
  if (!out.scatters || !(out.lobes.transmission > 0.0f)) return std::nullopt;
  // Straight through, the microfacet normal is the surface's: the Fresnel of wo itself, and every
  // layer above takes its share at the same cosine on both sides.
  const glm::vec3 transmittance = out.coat_share * out.sheen_share * transmission_ * base_color_ *
                                  (1.0f - max_component(dielectric_fresnel(out.o.z, 1.0f, 1.0f)));
  return PassThrough{transmittance, out.lobes.transmission};
}

std::optional<BsdfSample> Bsdf::sample(glm::vec3 wo, glm::vec3 u) const {
  const Outgoing& out = outgoing(wo);
  if (!out.scatters) return std::nullopt;
  const glm::vec3& o = out.o;
  const bool front = out.front;
  const Lobes& lobes = out.lobes;
  // Each lobe's draw must land where that lobe's own density is non-zero (a reflection on wo's
  // side, a transmission across), or the mixture's pdf would not count the way it got there.
  float pick = u.x;
  glm::vec3 wi;
  if ((pick -= lobes.coat) < 0.0f) {
    const glm::vec3& oc = out.coat_o;
    const float side = glm::dot(wo, coat_normal_) < 0.0f ? -1.0f : 1.0f;
    glm::vec3 ic = reflect(oc, Ggx{clearcoat_alpha_}.sample_visible(oc, u.y, u.z));
    if (!(ic.z > 0.0f)) return std::nullopt;
    ic.z *= side;
    wi = ic.x * coat_tangent_ + ic.y * coat_bitangent_ + ic.z * coat_normal_;
  } else {
    glm::vec3 i;
    const Ggx ggx{alpha_};
    if ((pick -= lobes.sheen) < 0.0f) {
      i = sample_cosine(u.y, u.z);
    } else if ((pick -= lobes.specular) < 0.0f) {
      i = reflect(o, ggx.sample_visible(o, u.y, u.z));
      if (!(i.z > 0.0f)) return std::nullopt;
    } else if ((pick -= lobes.transmission) < 0.0f) {
      if (thin_walled_ && smooth_) {
        const std::optional<PassThrough> through = pass_through(wo);
        if (!through) return std::nullopt;
        return BsdfSample{-wo, through->transmittance / through->probability, through->probability, true};
      }
      const glm::vec3 h = ggx.sample_visible(o, u.y, u.z);
      if (thin_walled_) {
        i = mirror(reflect(o, h));
      } else {
        const glm::vec2 eta = indices(front);
        const std::optional<glm::vec3> refracted = refract(o, h, eta.y / eta.x);
        if (!refracted) return std::nullopt;
        i = *refracted;
      }
      if (!(i.z < 0.0f)) return std::nullopt;
    } else if (lobes.diffuse > 0.0f) {
      i = sample_cosine(u.y, u.z);
    } else {
      return std::nullopt;  // nothing scatters (or u.x within rounding of 1)
    }
    if (!front) i.z = -i.z;
    wi = i.x * tangent_ + i.y * bitangent_ + i.z * normal_;
  }
  // Weight and pdf from the world direction returned, so that they agree with eval() and pdf()
  // for it to the last bit, as MIS against light samples needs.
  const Value value = evaluate(wo, wi);
  if (!(value.pdf > 0.0f)) return std::nullopt;
  return BsdfSample{wi, value.f_cos / value.pdf, value.pdf};
}

}  // namespace tracer
