// Tests of the path tracer's glTF BSDF (the metallic-roughness model with KHR_materials_ior,
// _specular, _transmission, _volume, _clearcoat and _sheen), in the manner of pbrt-v4's BSDF
// tests: sample() agrees with eval() and pdf(), sample() draws from pdf() (chi-square, every lobe
// alone and mixed, both sides of the surface), every lobe is reciprocal, no material reflects and
// transmits more than it receives and the energy-preserving ones exactly what they receive (white
// furnace), and the Fresnel limits at normal and grazing incidence. Deterministic: Philox with
// fixed keys throughout.

#include "tracer/bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "lightsampler/random.h"
#include "support/chi_square.h"

namespace tracer {
namespace {

using glm::vec3;

constexpr float kPi = std::numbers::pi_v<float>;

/// Four uniforms in [0, 1): draw `index` of stream `stream`.
glm::vec4 uniforms(std::uint32_t stream, std::uint32_t index) {
  const lightsampler::PhiloxCounter bits = lightsampler::philox4x32({index, 0, 0, 0}, {stream, 0x62736466u});
  return {lightsampler::uniform_float(bits[0]), lightsampler::uniform_float(bits[1]),
          lightsampler::uniform_float(bits[2]), lightsampler::uniform_float(bits[3])};
}

/// The unit direction at (cos theta, phi) about +z.
vec3 spherical(float cos_theta, float phi) {
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

vec3 uniform_sphere(float u1, float u2) { return spherical(1.0f - 2.0f * u1, 2.0f * kPi * u2); }

bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// |a - b| <= tolerance max(|a|, |b|), channel by channel.
testing::AssertionResult relatively_equal(vec3 a, vec3 b, float tolerance) {
  for (int c = 0; c < 3; ++c) {
    if (std::abs(a[c] - b[c]) > tolerance * std::max(std::abs(a[c]), std::abs(b[c])))
      return testing::AssertionFailure() << "channel " << c << ": " << a[c] << " vs " << b[c];
  }
  return testing::AssertionSuccess();
}

SurfaceParams metal_roughness(vec3 base, float metallic, float roughness) { return {base, metallic, roughness}; }

SurfaceParams thin_glass(vec3 base, float roughness) {
  SurfaceParams p{base, 0.0f, roughness};
  p.transmission = 1.0f;
  return p;
}

SurfaceParams volume_glass(vec3 base, float roughness, float ior) {
  SurfaceParams p = thin_glass(base, roughness);
  p.thin_walled = false;
  p.ior = ior;
  return p;
}

SurfaceParams coated(SurfaceParams p, float clearcoat, float roughness, vec3 normal = vec3(0.0f)) {
  p.clearcoat = clearcoat;
  p.clearcoat_roughness = roughness;
  p.clearcoat_normal = normal;
  return p;
}

SurfaceParams with_sheen(SurfaceParams p, vec3 colour, float roughness) {
  p.sheen_color = colour;
  p.sheen_roughness = roughness;
  return p;
}

SurfaceParams with_specular(SurfaceParams p, float specular, vec3 colour, float ior) {
  p.specular = specular;
  p.specular_color = colour;
  p.ior = ior;
  return p;
}

/// A material of the tests, named for messages.
struct Named {
  std::string name;
  SurfaceParams params;
};

/// Every lobe alone where it can be, and mixed: each property must hold for each.
const std::vector<Named> kMaterials = {
    {"rough white dielectric", metal_roughness(vec3(1.0f), 0.0f, 1.0f)},
    {"smooth white dielectric", metal_roughness(vec3(1.0f), 0.0f, 0.0f)},
    {"glossy dielectric", metal_roughness(vec3(1.0f), 0.0f, 0.3f)},
    {"smooth metal", metal_roughness(vec3(1.0f), 1.0f, 0.0f)},
    {"rough metal", metal_roughness({0.9f, 0.6f, 0.3f}, 1.0f, 0.6f)},
    {"half metal", metal_roughness({0.8f, 0.3f, 0.1f}, 0.5f, 0.5f)},
    {"black", metal_roughness(vec3(0.0f), 0.0f, 0.3f)},
    {"rough thin glass", thin_glass({0.9f, 0.7f, 0.5f}, 0.4f)},
    {"smooth thin glass", thin_glass(vec3(1.0f), 0.0f)},
    {"half-transmissive thin", [] {
       SurfaceParams p = thin_glass({0.3f, 0.8f, 0.6f}, 0.6f);
       p.transmission = 0.5f;
       return p;
     }()},
    {"rough glass volume", volume_glass(vec3(1.0f), 0.3f, 1.5f)},
    {"glossy water volume", volume_glass({0.8f, 0.9f, 1.0f}, 0.1f, 1.33f)},
    // Without a specular layer the boundary still reflects totally from inside.
    {"glass volume without specular", with_specular(volume_glass(vec3(1.0f), 0.2f, 1.5f), 0.0f, vec3(1.0f), 1.5f)},
    {"clearcoat over red", coated(metal_roughness({0.8f, 0.1f, 0.1f}, 0.0f, 0.7f), 1.0f, 0.2f)},
    {"tilted clearcoat", coated(metal_roughness(vec3(0.5f), 0.3f, 0.5f), 0.7f, 0.4f,
                                glm::normalize(vec3(0.3f, 0.1f, 1.0f)))},
    {"sheen on dark fabric", with_sheen(metal_roughness(vec3(0.05f), 0.0f, 1.0f), {1.0f, 0.0f, 0.0f}, 0.5f)},
    {"specular colour", with_specular(metal_roughness({0.2f, 0.4f, 0.3f}, 0.0f, 0.35f), 0.5f, {1.0f, 0.5f, 0.2f}, 1.8f)},
    {"ior 0 (Fresnel 1)", with_specular(metal_roughness(vec3(0.6f), 0.0f, 0.4f), 1.0f, vec3(1.0f), 0.0f)},
    {"everything", with_sheen(coated(with_specular(thin_glass({0.7f, 0.8f, 0.9f}, 0.5f), 0.8f, {1.0f, 0.9f, 0.8f}, 1.4f),
                                     0.5f, 0.3f),
                              {0.3f, 0.3f, 0.6f}, 0.3f)},
};

/// A random unit normal and a wo on either side of it, for a material's config-th case.
std::pair<vec3, vec3> normal_and_wo(std::uint32_t stream, std::uint32_t index) {
  const glm::vec4 g = uniforms(stream, index);
  return {uniform_sphere(g.x, g.y), uniform_sphere(g.z, g.w)};
}

TEST(Bsdf, SampleWeightIsEvalOverPdf) {
  // For random normals and wo on either side: a sampled wi's pdf is pdf(wo, wi) and its weight
  // eval(wo, wi) / pdf(wo, wi), both to 1e-6 relative (sample() evaluates the direction it
  // returns, so only the test's own division may round differently). A pass-through goes
  // straight on, with pdf its probability and weight pass_through()'s transmittance over it.
  for (std::uint32_t m = 0; m < kMaterials.size(); ++m) {
    SCOPED_TRACE(kMaterials[m].name);
    int drawn = 0, returned = 0;
    for (std::uint32_t config = 0; config < 32; ++config) {
      const auto [normal, wo] = normal_and_wo(1, m * 32 + config);
      const Bsdf bsdf(kMaterials[m].params, normal);
      for (std::uint32_t k = 0; k < 64; ++k) {
        const auto s = bsdf.sample(wo, vec3(uniforms(2, (m * 32 + config) * 64 + k)));
        ++drawn;
        if (!s) continue;
        ++returned;
        ASSERT_GT(s->pdf, 0.0f);
        ASSERT_TRUE(finite(s->weight));
        EXPECT_NEAR(glm::length(s->wi), 1.0f, 1e-5f);
        if (s->pass_through) {
          const auto through = bsdf.pass_through(wo);
          ASSERT_TRUE(through.has_value());
          EXPECT_EQ(s->wi, -wo);
          EXPECT_EQ(s->pdf, through->probability);
          EXPECT_TRUE(relatively_equal(s->weight * s->pdf, through->transmittance, 1e-6f));
          continue;
        }
        EXPECT_NEAR(s->pdf, bsdf.pdf(wo, s->wi), 1e-6f * s->pdf);
        EXPECT_TRUE(relatively_equal(s->weight, bsdf.eval(wo, s->wi) / bsdf.pdf(wo, s->wi), 1e-6f));
      }
    }
    // Only visible normals that reflect or refract to the wrong side miss (and, inside a volume,
    // refractions beyond the critical angle), and black scatters nothing.
    if (kMaterials[m].name != "black") {
      EXPECT_GT(returned, drawn * 2 / 3);
    }
  }
}

/// Chi-square table: (cos theta, phi) about +z over the whole sphere, kCosBins x kPhiBins cells of
/// equal solid angle, plus one cell for the pass-through and one for draws that return nothing.
constexpr int kCosBins = 20, kPhiBins = 40;

/// The integral of pdf() over cell (i, j), where the solid angle element is d(cos theta) d(phi):
/// 16 x 16 sub-cells, 2 x 2 Gauss-Legendre points each. Gauss points avoid the cell edges, where
/// the pdf jumps to 0 at the horizon.
double integrate_cell(const Bsdf& bsdf, vec3 wo, int i, int j) {
  constexpr int kSub = 16;
  const double dc = 2.0 / kCosBins / kSub, dp = 2.0 * std::numbers::pi / kPhiBins / kSub;
  const double offsets[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double sum = 0;
  for (int a = 0; a < 2 * kSub; ++a) {
    for (int b = 0; b < 2 * kSub; ++b) {
      const double c = -1.0 + 2.0 * i / kCosBins + (a / 2 + offsets[a % 2]) * dc;
      const double p = 2.0 * std::numbers::pi * j / kPhiBins + (b / 2 + offsets[b % 2]) * dp;
      sum += bsdf.pdf(wo, spherical(float(c), float(p)));
    }
  }
  return sum * dc * dp / 4.0;
}

/// Bins `draws` directions of sampler.sample(wo, .) and compares them with the counts that
/// claimed.pdf(wo, .) and claimed.pass_through(wo) predict.
trs_test::ChiSquareResult chi_square(const Bsdf& sampler, const Bsdf& claimed, vec3 wo, std::uint32_t stream,
                                     int draws) {
  constexpr int kCells = kCosBins * kPhiBins, kPass = kCells, kMiss = kCells + 1;
  std::vector<double> observed(kCells + 2, 0.0), expected(kCells + 2, 0.0);
  for (int k = 0; k < draws; ++k) {
    const auto s = sampler.sample(wo, vec3(uniforms(stream, std::uint32_t(k))));
    if (!s) {
      observed[kMiss] += 1;
      continue;
    }
    if (s->pass_through) {
      observed[kPass] += 1;
      continue;
    }
    const int i = std::clamp(int((s->wi.z + 1.0f) * 0.5f * kCosBins), 0, kCosBins - 1);
    const float phi = std::atan2(s->wi.y, s->wi.x);
    const int j = std::clamp(int((phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi) * kPhiBins), 0, kPhiBins - 1);
    observed[i * kPhiBins + j] += 1;
  }
  double total = 0;
  for (int i = 0; i < kCosBins; ++i) {
    for (int j = 0; j < kPhiBins; ++j) {
      expected[i * kPhiBins + j] = draws * integrate_cell(claimed, wo, i, j);
      total += expected[i * kPhiBins + j];
    }
  }
  const auto through = claimed.pass_through(wo);
  expected[kPass] = through ? draws * double(through->probability) : 0.0;
  // Quadrature error may push the total a hair over the draws; the miss cell cannot go negative.
  expected[kMiss] = std::max(0.0, draws - total - expected[kPass]);
  return trs_test::chi_square_test(observed, expected);
}

/// A material, wo (cos theta in the x-z plane) and the given normal, +z or -z.
struct ChiSquareCase {
  std::string name;
  SurfaceParams params;
  float cos_wo;
  float normal_z;
};

const std::vector<ChiSquareCase> kChiSquareCases = {
    {"dielectric, mostly diffuse", metal_roughness(vec3(1.0f), 0.0f, 0.5f), 0.8f, 1.0f},
    {"metal, normal on the far side", metal_roughness({0.9f, 0.6f, 0.3f}, 1.0f, 0.4f), 0.5f, -1.0f},
    {"half metal, grazing", metal_roughness(vec3(0.7f), 0.5f, 1.0f), 0.15f, 1.0f},
    {"coloured, head-on", metal_roughness({0.2f, 0.5f, 0.8f}, 0.2f, 0.7f), 1.0f, 1.0f},
    {"rough thin transmission", thin_glass({0.9f, 0.7f, 0.5f}, 0.5f), 0.6f, 1.0f},
    // Without the specular layer (whose smooth reflection is too sharp for the quadrature): the
    // pass-through beside the diffuse.
    {"smooth thin transmission beside diffuse", [] {
       SurfaceParams p = with_specular(thin_glass({0.9f, 0.7f, 0.5f}, 0.0f), 0.0f, vec3(1.0f), 1.5f);
       p.transmission = 0.5f;
       return p;
     }(), 0.7f, 1.0f},
    {"refraction into glass", volume_glass(vec3(1.0f), 0.4f, 1.5f), 0.5f, 1.0f},
    {"refraction out of water", volume_glass(vec3(1.0f), 0.3f, 1.33f), 0.9f, -1.0f},
    {"total internal reflection without specular",
     with_specular(volume_glass(vec3(1.0f), 0.3f, 1.5f), 0.0f, vec3(1.0f), 1.5f), 0.5f, -1.0f},
    {"clearcoat", coated(metal_roughness({0.8f, 0.1f, 0.1f}, 0.0f, 0.8f), 1.0f, 0.15f), 0.4f, 1.0f},
    {"clearcoat on a tilted normal", coated(metal_roughness(vec3(0.5f), 0.0f, 0.6f), 1.0f, 0.3f,
                                            glm::normalize(vec3(0.4f, 0.0f, 1.0f))), 0.7f, 1.0f},
    {"sheen", with_sheen(metal_roughness(vec3(0.05f), 0.0f, 1.0f), vec3(1.0f), 0.4f), 0.3f, 1.0f},
    {"every lobe", kMaterials.back().params, 0.55f, 1.0f},
};

constexpr int kChiSquareDraws = 200000;

TEST(Bsdf, ChiSquareSampleMatchesPdf) {
  // H0: sample() draws wi (or the pass-through, or nothing) with the density pdf() and the
  // probability pass_through() gives. Per case: 200000 draws from Philox stream 20 + case, 20 x 40
  // cells over the sphere plus the pass-through and miss cells, expectations by quadrature of
  // pdf(), cells under 5 pooled, any draw in a cell of expectation 0 fails. Family-wise alpha 0.01
  // over the cases (Sidak).
  const double alpha = trs_test::sidak_alpha(0.01, kChiSquareCases.size());
  for (std::uint32_t c = 0; c < kChiSquareCases.size(); ++c) {
    const ChiSquareCase& test = kChiSquareCases[c];
    const Bsdf bsdf(test.params, vec3(0.0f, 0.0f, test.normal_z));
    const auto result = chi_square(bsdf, bsdf, spherical(test.cos_wo, 0.0f), 20 + c, kChiSquareDraws);
    EXPECT_GE(result.dof, 50.0) << test.name << ": too few cells to have power";
    EXPECT_TRUE(result.passes(alpha)) << test.name << ": " << result.describe();
  }
}

TEST(Bsdf, PdfIsPositiveWhereverEvalIs) {
  // A direction that carries light but that sample() can never draw would bias every estimate
  // that relies on BSDF sampling to reach it. For random normals, wo and wi on either side:
  // eval > 0 implies pdf > 0.
  for (std::uint32_t m = 0; m < kMaterials.size(); ++m) {
    for (std::uint32_t k = 0; k < 2000; ++k) {
      const auto [normal, wo] = normal_and_wo(40, m * 2000 + k);
      const glm::vec4 h = uniforms(41, m * 2000 + k);
      const vec3 wi = uniform_sphere(h.x, h.y);
      const Bsdf bsdf(kMaterials[m].params, normal);
      if (glm::length(bsdf.eval(wo, wi)) > 0.0f) {
        ASSERT_GT(bsdf.pdf(wo, wi), 0.0f) << kMaterials[m].name << ", draw " << k;
      }
    }
  }
}

TEST(Bsdf, ChiSquareRejectsWrongPdfs) {
  // The same check has power: draws that pass above, held against a wrong pdf, are rejected at
  // alpha 0.01. The metal against alpha = roughness rather than roughness^2; the refraction
  // against an index of 1.3 instead of 1.5; the sheen against a roughness of 0.8 instead of 0.4.
  const auto expect_rejected = [](const ChiSquareCase& test, SurfaceParams wrong, std::uint32_t stream) {
    const vec3 normal(0.0f, 0.0f, test.normal_z);
    const auto result = chi_square(Bsdf(test.params, normal), Bsdf(wrong, normal), spherical(test.cos_wo, 0.0f),
                                   stream, kChiSquareDraws);
    EXPECT_FALSE(result.passes(0.01)) << test.name << ": " << result.describe();
  };
  SurfaceParams metal = kChiSquareCases[1].params;
  metal.roughness = std::sqrt(metal.roughness);
  expect_rejected(kChiSquareCases[1], metal, 21);
  SurfaceParams glass = kChiSquareCases[6].params;
  glass.ior = 1.3f;
  expect_rejected(kChiSquareCases[6], glass, 26);
  SurfaceParams sheen = kChiSquareCases[11].params;
  sheen.sheen_roughness = 0.8f;
  expect_rejected(kChiSquareCases[11], sheen, 31);
}

/// The index of refraction on the side of `w` of a material's surface of normal `normal`.
float index_on_side(const SurfaceParams& params, vec3 normal, vec3 w) {
  if (params.thin_walled) return 1.0f;
  return glm::dot(w, normal) > 0.0f ? 1.0f : params.ior;
}

TEST(Bsdf, EveryLobeIsReciprocal) {
  // f(wo, wi) / eta(wo)^2 = f(wi, wo) / eta(wi)^2, f = eval / |cos wi|, for wi on either side:
  // plain reciprocity where both sides have the same index (every reflection, and thin
  // transmission), and that of refraction in radiance units across a volume's boundary. To 2e-4
  // relative, 1e-3 across a boundary: cosines, half vectors and table lookups round differently
  // the two ways round, the refraction's generalised half vector most.
  int compared = 0;
  for (std::uint32_t m = 0; m < kMaterials.size(); ++m) {
    const SurfaceParams& params = kMaterials[m].params;
    for (std::uint32_t k = 0; k < 300; ++k) {
      const auto [normal, wo] = normal_and_wo(5, m * 300 + k);
      const glm::vec4 h = uniforms(6, m * 300 + k);
      const vec3 wi = uniform_sphere(h.x, h.y);
      const Bsdf bsdf(params, normal);
      const float eta_o = index_on_side(params, normal, wo), eta_i = index_on_side(params, normal, wi);
      const vec3 forward = bsdf.eval(wo, wi) / (std::abs(glm::dot(wi, normal)) * eta_o * eta_o);
      const vec3 backward = bsdf.eval(wi, wo) / (std::abs(glm::dot(wo, normal)) * eta_i * eta_i);
      const float tolerance = eta_o == eta_i ? 2e-4f : 1e-3f;
      EXPECT_TRUE(relatively_equal(forward, backward, tolerance)) << kMaterials[m].name << ", draw " << k;
      compared += glm::length(forward) > 0.0f;
    }
  }
  EXPECT_GT(compared, 2000);
}

/// Mean and standard error of sample()'s weight per channel (0 for a miss) over `draws`: the
/// directional albedo, reflection and transmission together.
std::pair<glm::dvec3, glm::dvec3> albedo(const Bsdf& bsdf, vec3 wo, std::uint32_t stream, int draws) {
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int k = 0; k < draws; ++k) {
    const auto s = bsdf.sample(wo, vec3(uniforms(stream, std::uint32_t(k))));
    const glm::dvec3 w = s ? glm::dvec3(s->weight) : glm::dvec3(0.0);
    sum += w;
    sum2 += w * w;
  }
  const glm::dvec3 mean = sum / double(draws);
  return {mean, glm::sqrt(glm::max(glm::dvec3(0.0), sum2 / double(draws) - mean * mean) / double(draws))};
}

TEST(Bsdf, WhiteFurnaceAtMostOne) {
  // H0: no material reflects and transmits more than it receives. Every material above but the
  // volumes (whose refraction carries radiance across a change of index, in units that are not
  // conserved), white where it has a base colour, at head-on to grazing wo: E[weight] <= 1 per
  // channel to 4 standard errors plus 0.004, the tables' interpolation error.
  std::uint32_t stream = 100;
  for (const Named& material : kMaterials) {
    if (!material.params.thin_walled) continue;
    for (float cos_wo : {1.0f, 0.6f, 0.2f, 0.02f}) {
      const Bsdf bsdf(material.params, vec3(0.0f, 0.0f, 1.0f));
      const auto [mean, error] = albedo(bsdf, spherical(cos_wo, 0.0f), stream++, 20000);
      for (int c = 0; c < 3; ++c)
        EXPECT_LE(mean[c], 1.004 + 4 * error[c]) << material.name << ", cos wo " << cos_wo << ", channel " << c;
    }
  }
}

TEST(Bsdf, WhiteFurnaceIsOneWhereEnergyIsPreserved) {
  // H0: these white materials reflect and transmit all they receive. An opaque dielectric at any
  // roughness (its diffuse takes what its layer does not reflect: the coupling of albedo_tables.h);
  // smooth thin glass (reflection F, pass-through 1 - F); a smooth metal (a mirror of F = 1, its
  // masking negligible at alpha 1e-3); and the same under a smooth clearcoat, which takes from the
  // base what it reflects. 40000 draws, 4 standard errors plus 0.006 for the tables'
  // interpolation, head-on to grazing.
  const std::vector<Named> preserving = {
      {"rough dielectric", metal_roughness(vec3(1.0f), 0.0f, 1.0f)},
      {"glossy dielectric", metal_roughness(vec3(1.0f), 0.0f, 0.3f)},
      {"smooth dielectric", metal_roughness(vec3(1.0f), 0.0f, 0.0f)},
      {"specular colour", with_specular(metal_roughness(vec3(1.0f), 0.0f, 0.5f), 0.7f, vec3(1.0f), 1.7f)},
      {"smooth thin glass", thin_glass(vec3(1.0f), 0.0f)},
      {"smooth metal", metal_roughness(vec3(1.0f), 1.0f, 0.0f)},
      {"smooth coat on a smooth metal", coated(metal_roughness(vec3(1.0f), 1.0f, 0.0f), 1.0f, 0.0f)},
  };
  std::uint32_t stream = 200;
  for (const Named& material : preserving) {
    for (float cos_wo : {1.0f, 0.5f, 0.1f}) {
      const Bsdf bsdf(material.params, vec3(0.0f, 0.0f, 1.0f));
      const auto [mean, error] = albedo(bsdf, spherical(cos_wo, 0.0f), stream++, 40000);
      EXPECT_NEAR(mean.x, 1.0, 0.006 + 4 * error.x) << material.name << ", cos wo " << cos_wo;
    }
  }
}

TEST(Bsdf, FresnelLimits) {
  // Straight through a smooth thin pane of index 1.5, head-on: 1 - F0 = 0.96 of the base colour;
  // at grazing F -> 1 and nothing goes through. Index 1 reflects nothing head-on (F0 = 0), and
  // Schlick's (1 - cos)^5 at an angle; index 0 (the specification's special value) reflects
  // everything: nothing passes. A smooth metal reflects its base colour head-on (F0) and white at
  // grazing (F90 = 1).
  const vec3 up(0.0f, 0.0f, 1.0f);
  const vec3 tint(0.9f, 0.5f, 0.2f);
  const auto pane = Bsdf(thin_glass(tint, 0.0f), up);
  const auto head_on = pane.pass_through(up);
  ASSERT_TRUE(head_on.has_value());
  EXPECT_TRUE(relatively_equal(head_on->transmittance, 0.96f * tint, 1e-5f));
  const auto grazing = pane.pass_through(spherical(1e-4f, 0.0f));
  ASSERT_TRUE(grazing.has_value());
  EXPECT_LT(grazing->transmittance.x, 1e-3f);
  SurfaceParams index_one = thin_glass(vec3(1.0f), 0.0f);
  index_one.ior = 1.0f;
  for (float cos_wo : {1.0f, 0.3f}) {
    const auto through = Bsdf(index_one, up).pass_through(spherical(cos_wo, 0.0f));
    ASSERT_TRUE(through.has_value());
    EXPECT_NEAR(through->transmittance.x, 1.0f - std::pow(1.0f - cos_wo, 5.0f), 1e-6f);
  }
  SurfaceParams index_zero = thin_glass(vec3(1.0f), 0.0f);
  index_zero.ior = 0.0f;
  const auto none = Bsdf(index_zero, up).pass_through(up);
  EXPECT_TRUE(!none.has_value() || none->transmittance == vec3(0.0f));
  // The mirror, by the albedo of its nearly singular lobe (its masking negligible): F0 head-on,
  // and at cosine 0.01 Schlick's F = F0 + (1 - F0) 0.99^5.
  const Bsdf mirror(metal_roughness(tint, 1.0f, 0.0f), up);
  const auto [normal_incidence, error] = albedo(mirror, up, 300, 2000);
  EXPECT_NEAR(normal_incidence.x, tint.x, 1e-3);
  EXPECT_NEAR(normal_incidence.z, tint.z, 1e-3);
  const auto [at_grazing, grazing_error] = albedo(mirror, spherical(0.01f, 0.0f), 301, 2000);
  const double expected = tint.z + (1.0 - tint.z) * std::pow(0.99, 5.0);
  EXPECT_NEAR(at_grazing.z, expected, 0.02);
}

TEST(Bsdf, TotalInternalReflection) {
  // From inside smooth glass (index 1.5), beyond the critical angle (sin > 1 / 1.5) light leaves
  // the volume only through the GGX's tails (alpha 1e-3), whose microfacets tilt far enough now
  // and then: under 0.5 % of 20000 draws. Inside the critical angle, most of it leaves.
  const vec3 up(0.0f, 0.0f, 1.0f);
  const Bsdf glass(volume_glass(vec3(1.0f), 0.0f, 1.5f), up);
  const vec3 beyond = spherical(-0.5f, 0.0f);  // sin 0.87 > 0.67, seen from inside (below)
  int escaped = 0;
  for (std::uint32_t k = 0; k < 20000; ++k) {
    const auto s = glass.sample(beyond, vec3(uniforms(310, k)));
    escaped += s && glm::dot(s->wi, up) > 0.0f;
  }
  EXPECT_LT(escaped, 100);
  const vec3 within = spherical(-0.95f, 0.0f);
  int left = 0;
  for (std::uint32_t k = 0; k < 2000; ++k) {
    const auto s = glass.sample(within, vec3(uniforms(311, k)));
    left += s && glm::dot(s->wi, up) > 0.0f;
  }
  EXPECT_GT(left, 1000);
}

TEST(Bsdf, ThinSurfacesAreTwoSided) {
  // For a thin material, flipping the given normal changes nothing (to 1e-5 relative: the two
  // frames round differently). A material that does not transmit has eval and pdf 0 across.
  for (std::uint32_t k = 0; k < 500; ++k) {
    const Named& material = kMaterials[k % kMaterials.size()];
    if (!material.params.thin_walled || material.params.clearcoat_normal != vec3(0.0f)) continue;
    const auto [normal, wo] = normal_and_wo(7, k);
    const glm::vec4 h = uniforms(8, k);
    const vec3 wi = uniform_sphere(h.x, h.y);
    const Bsdf bsdf(material.params, normal), flipped(material.params, -normal);
    EXPECT_TRUE(relatively_equal(bsdf.eval(wo, wi), flipped.eval(wo, wi), 1e-5f)) << material.name << " " << k;
    EXPECT_NEAR(bsdf.pdf(wo, wi), flipped.pdf(wo, wi), 1e-5f * bsdf.pdf(wo, wi)) << material.name << " " << k;
    if (material.params.transmission == 0.0f) {
      const vec3 across = glm::dot(wi, normal) * glm::dot(wo, normal) < 0.0f ? wi : glm::reflect(wi, normal);
      EXPECT_EQ(bsdf.eval(wo, across), vec3(0.0f));
      EXPECT_EQ(bsdf.pdf(wo, across), 0.0f);
    }
  }
}

TEST(Bsdf, FiniteAtEdgeCases) {
  // Axis normals (including -z, where the basis construction switches branch), wo and wi head-on,
  // grazing, tangent and opposite: eval and pdf finite and >= 0; a tangent wo samples nothing.
  const std::vector<vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, glm::normalize(vec3(1e-4f, 0, -1))};
  const std::vector<vec3> directions = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0},
                                        {-1, 0, 0}, spherical(1e-7f, 0.0f), spherical(-1e-7f, 0.0f),
                                        spherical(1e-4f, 2.0f), spherical(0.5f, 3.0f)};
  for (const Named& material : kMaterials) {
    SCOPED_TRACE(material.name);
    for (vec3 normal : normals) {
      const Bsdf bsdf(material.params, normal);
      for (vec3 wo : directions) {
        for (vec3 wi : directions) {
          const vec3 f = bsdf.eval(wo, wi);
          const float pdf = bsdf.pdf(wo, wi);
          EXPECT_TRUE(finite(f) && glm::all(glm::greaterThanEqual(f, vec3(0.0f))));
          EXPECT_TRUE(std::isfinite(pdf) && pdf >= 0.0f);
        }
        for (std::uint32_t k = 0; k < 16; ++k) {
          const auto s = bsdf.sample(wo, vec3(uniforms(9, k)));
          if (s) {
            EXPECT_TRUE(finite(s->weight) && std::isfinite(s->pdf) && finite(s->wi));
          }
          if (glm::dot(wo, normal) == 0.0f) {
            EXPECT_FALSE(s.has_value());
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace tracer
