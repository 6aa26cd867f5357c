// Tests of the path tracer's glTF metallic-roughness BSDF: sample() agrees with eval() and pdf(),
// pdf() is normalised, no material reflects more than it receives, the metal lobe is reciprocal,
// and sample() draws from pdf() (chi-square). Deterministic: Philox with fixed keys throughout.

#include "tracer/bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
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

/// The corners of metallic x roughness, a coloured mixture and black: every property must hold for each.
const std::vector<SurfaceParams> kMaterials = {
    {vec3(1.0f), 0.0f, 0.0f}, {vec3(1.0f), 0.0f, 1.0f},       {vec3(1.0f), 1.0f, 0.0f},
    {vec3(1.0f), 1.0f, 1.0f}, {vec3(1.0f), 0.0f, 0.3f},       {{0.8f, 0.3f, 0.1f}, 0.5f, 0.5f},
    {vec3(0.0f), 0.0f, 0.3f}, {vec3(0.0f), 1.0f, 0.6f},       {{0.2f, 0.5f, 0.9f}, 0.3f, 0.1f},
};

TEST(Bsdf, SampleWeightIsEvalOverPdf) {
  // For random normals and wo on either side: a sampled wi lies on wo's side, its pdf is pdf(wo, wi)
  // and its weight eval(wo, wi) / pdf(wo, wi), both to 1e-6 relative (sample() evaluates the
  // direction it returns, so only the test's own division may round differently).
  int drawn = 0, returned = 0;
  for (std::uint32_t m = 0; m < kMaterials.size(); ++m) {
    for (std::uint32_t config = 0; config < 32; ++config) {
      const glm::vec4 g = uniforms(1, m * 32 + config);
      const vec3 normal = uniform_sphere(g.x, g.y);
      const vec3 wo = uniform_sphere(g.z, g.w);
      const Bsdf bsdf(kMaterials[m], normal);
      for (std::uint32_t k = 0; k < 64; ++k) {
        const glm::vec4 u = uniforms(2, (m * 32 + config) * 64 + k);
        const auto s = bsdf.sample(wo, vec3(u));
        ++drawn;
        if (!s) continue;
        ++returned;
        ASSERT_GT(s->pdf, 0.0f);
        ASSERT_TRUE(finite(s->weight));
        EXPECT_GT(glm::dot(s->wi, normal) * glm::dot(wo, normal), 0.0f) << "wi not on the side of wo";
        EXPECT_NEAR(glm::length(s->wi), 1.0f, 1e-5f);
        EXPECT_NEAR(s->pdf, bsdf.pdf(wo, s->wi), 1e-6f * s->pdf);
        EXPECT_TRUE(relatively_equal(s->weight, bsdf.eval(wo, s->wi) / bsdf.pdf(wo, s->wi), 1e-6f));
      }
    }
  }
  // Only visible normals that reflect below the horizon miss: a few per cent at most.
  EXPECT_GT(returned, drawn * 9 / 10);
}

TEST(Bsdf, PdfIntegratesToAcceptanceRate) {
  // The integral of pdf() over the sphere is the probability that sample() returns a direction,
  // and so at most 1. It falls short of 1 by the visible normals that reflect wo below the horizon:
  // head-on, those tilted past 45 degrees, a fraction alpha^2 / (1 + alpha^2) of the GGX's
  // projected area, so a metal's integral is then 1 / (1 + alpha^2) (0.5 at roughness 1), while a
  // rough white dielectric, mostly diffuse, loses a few per cent at most.
  // Integral by jittered-stratified uniform sphere sampling, 256 x 512 strata: error <= 0.0025 for
  // roughness >= 0.5 (measured over seeds; sharper lobes need many more strata and are left to the
  // chi-square test, whose miss cell checks the same integral by quadrature). Acceptance from
  // 150000 draws (standard error <= 0.0013, at acceptance 0.5). Tolerance 0.006 between the two,
  // 0.001 against the closed form.
  constexpr int kCos = 256, kPhi = 512, kDraws = 150000;
  for (std::uint32_t m = 0; m < kMaterials.size(); ++m) {
    const SurfaceParams& params = kMaterials[m];
    if (params.roughness < 0.5f) continue;
    for (float cos_wo : {1.0f, 0.5f, 0.05f}) {
      const vec3 wo = spherical(cos_wo, 0.0f);
      const Bsdf bsdf(params, vec3(0.0f, 0.0f, 1.0f));
      double integral = 0;
      for (int i = 0; i < kCos; ++i) {
        for (int j = 0; j < kPhi; ++j) {
          const glm::vec4 u = uniforms(3, std::uint32_t(i * kPhi + j));
          integral += bsdf.pdf(wo, uniform_sphere((float(i) + u.x) / kCos, (float(j) + u.y) / kPhi));
        }
      }
      integral *= 4.0 * std::numbers::pi / (kCos * kPhi);
      int accepted = 0;
      for (std::uint32_t k = 0; k < kDraws; ++k) accepted += bsdf.sample(wo, vec3(uniforms(4, k))).has_value();
      SCOPED_TRACE(testing::Message() << "material " << m << " cos wo " << cos_wo);
      EXPECT_NEAR(integral, double(accepted) / kDraws, 0.006);
      EXPECT_LE(integral, 1.0025);
      if (params.metallic == 1.0f && cos_wo == 1.0f) {
        EXPECT_NEAR(integral, 1.0 / (1.0 + std::pow(params.roughness, 4.0)), 0.001);
      }
      if (params.metallic == 0.0f) {
        EXPECT_GE(integral, 0.94);
      }
    }
  }
}

/// Mean and standard error of the red channel of sample()'s weight (0 for a miss) over `draws`.
std::pair<double, double> albedo(const Bsdf& bsdf, vec3 wo, std::uint32_t stream, int draws) {
  double sum = 0, sum2 = 0;
  for (int k = 0; k < draws; ++k) {
    const auto s = bsdf.sample(wo, vec3(uniforms(stream, std::uint32_t(k))));
    const double w = s ? s->weight.x : 0.0;
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / draws;
  return {mean, std::sqrt(std::max(0.0, sum2 / draws - mean * mean) / draws)};
}

TEST(Bsdf, AlbedoAtMostOne) {
  // White base colour (the channels are then equal): E[weight] <= 1 over metallic {0, 0.5, 1} x
  // roughness {0, 0.3, 0.6, 1} x head-on to grazing wo, 20000 draws each, to 4 standard errors plus
  // 0.0015. That margin is the model's own: weighting the diffuse by 1 - F(n.wo) leaves room for
  // the specular layer's F(n.wo), while its visible normals average a Schlick F that is convex in
  // wo.h, so a white dielectric reflects up to about 1.0013 (roughness 0.3, n.wo 0.6, by quadrature).
  std::uint32_t stream = 100;
  for (float metallic : {0.0f, 0.5f, 1.0f}) {
    for (float roughness : {0.0f, 0.3f, 0.6f, 1.0f}) {
      for (float cos_wo : {1.0f, 0.6f, 0.2f, 0.02f}) {
        const Bsdf bsdf({vec3(1.0f), metallic, roughness}, vec3(0.0f, 0.0f, 1.0f));
        const auto [mean, error] = albedo(bsdf, spherical(cos_wo, 0.0f), stream++, 20000);
        EXPECT_LE(mean, 1.0015 + 4 * error)
            << "metallic " << metallic << " roughness " << roughness << " cos wo " << cos_wo;
      }
    }
  }
}

TEST(Bsdf, AlbedoOfWhiteSurfacesHeadOn) {
  // Head-on, Schlick's F is F0. White rough dielectric: the diffuse lobe alone reflects exactly
  // 1 - F0 = 0.96, and the specular lobe adds F0 times its single-scattering albedo (0 to 1), so
  // the albedo lies in [0.96, 1]. A smooth white metal is a mirror with F = 1 and negligible
  // masking at alpha 1e-3: albedo 1 to 0.001. 100000 draws; 4 standard errors of slack.
  const vec3 up(0.0f, 0.0f, 1.0f);
  const auto [dielectric, dielectric_error] = albedo(Bsdf({vec3(1.0f), 0.0f, 1.0f}, up), up, 200, 100000);
  EXPECT_GE(dielectric, 0.96 - 4 * dielectric_error);
  EXPECT_LE(dielectric, 1.0 + 4 * dielectric_error);
  const auto [mirror, mirror_error] = albedo(Bsdf({vec3(1.0f), 1.0f, 0.0f}, up), up, 201, 100000);
  EXPECT_NEAR(mirror, 1.0, 0.001 + 4 * mirror_error);
}

TEST(Bsdf, MetalIsReciprocal) {
  // f(wo, wi) = eval(wo, wi) / |cos wi| is symmetric for metals, to 1e-4 relative (float rounding
  // of cosines and of the Fresnel term at wo.h vs wi.h). Only metals: the diffuse term's weight
  // 1 - F(n.wo) depends on wo alone, so dielectrics are not reciprocal by design.
  for (float roughness : {0.0f, 0.1f, 0.5f, 1.0f}) {
    for (std::uint32_t k = 0; k < 200; ++k) {
      const glm::vec4 g = uniforms(5, k), h = uniforms(6, k);
      const vec3 normal = uniform_sphere(g.x, g.y);
      const vec3 wo = uniform_sphere(g.z, g.w);
      vec3 wi = uniform_sphere(h.x, h.y);
      if (glm::dot(wi, normal) * glm::dot(wo, normal) < 0.0f) wi = glm::reflect(wi, normal);  // same side
      const Bsdf bsdf({{0.9f, 0.6f, 0.3f}, 1.0f, roughness}, normal);
      const vec3 forward = bsdf.eval(wo, wi) / std::abs(glm::dot(wi, normal));
      const vec3 backward = bsdf.eval(wi, wo) / std::abs(glm::dot(wo, normal));
      EXPECT_TRUE(relatively_equal(forward, backward, 1e-4f)) << "roughness " << roughness << " draw " << k;
    }
  }
}

TEST(Bsdf, TwoSidedReflectionOnly) {
  // Flipping the given normal changes nothing (to 1e-5 relative: the two frames round differently);
  // wi on the other side of the surface from wo has eval and pdf 0.
  for (std::uint32_t k = 0; k < 500; ++k) {
    const glm::vec4 g = uniforms(7, k), h = uniforms(8, k);
    const SurfaceParams& params = kMaterials[k % kMaterials.size()];
    const vec3 normal = uniform_sphere(g.x, g.y);
    const vec3 wo = uniform_sphere(g.z, g.w);
    const vec3 wi = uniform_sphere(h.x, h.y);
    const Bsdf bsdf(params, normal), flipped(params, -normal);
    EXPECT_TRUE(relatively_equal(bsdf.eval(wo, wi), flipped.eval(wo, wi), 1e-5f)) << "draw " << k;
    EXPECT_NEAR(bsdf.pdf(wo, wi), flipped.pdf(wo, wi), 1e-5f * bsdf.pdf(wo, wi)) << "draw " << k;
    const vec3 across = glm::dot(wi, normal) * glm::dot(wo, normal) < 0.0f ? wi : glm::reflect(wi, normal);
    EXPECT_EQ(bsdf.eval(wo, across), vec3(0.0f));
    EXPECT_EQ(bsdf.pdf(wo, across), 0.0f);
  }
}

TEST(Bsdf, FiniteAtEdgeCases) {
  // Axis normals (including -z, where the basis construction switches branch), wo and wi head-on,
  // grazing, tangent and opposite: eval and pdf finite and >= 0; a tangent wo samples nothing.
  const std::vector<vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, glm::normalize(vec3(1e-4f, 0, -1))};
  const std::vector<vec3> directions = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0},
                                        {-1, 0, 0}, spherical(1e-7f, 0.0f), spherical(-1e-7f, 0.0f),
                                        spherical(1e-4f, 2.0f), spherical(0.5f, 3.0f)};
  for (const SurfaceParams& params : kMaterials) {
    for (vec3 normal : normals) {
      const Bsdf bsdf(params, normal);
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

/// Chi-square table: (cos theta, phi) about +z over the whole sphere, kCosBins x kPhiBins cells of
/// equal solid angle, plus one cell for draws that return nothing.
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
/// claimed.pdf(wo, .) predicts.
trs_test::ChiSquareResult chi_square(const Bsdf& sampler, const Bsdf& claimed, vec3 wo, std::uint32_t stream,
                                     int draws) {
  constexpr int kCells = kCosBins * kPhiBins;
  std::vector<double> observed(kCells + 1, 0.0), expected(kCells + 1, 0.0);
  for (int k = 0; k < draws; ++k) {
    const auto s = sampler.sample(wo, vec3(uniforms(stream, std::uint32_t(k))));
    if (!s) {
      observed[kCells] += 1;
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
  // Quadrature error may push the total a hair over the draws; the miss cell cannot go negative.
  expected[kCells] = std::max(0.0, draws - total);
  return trs_test::chi_square_test(observed, expected);
}

/// A material, wo (cos theta in the x-z plane) and the given normal, +z or -z.
struct ChiSquareCase {
  SurfaceParams params;
  float cos_wo;
  float normal_z;
};

const std::vector<ChiSquareCase> kChiSquareCases = {
    {{vec3(1.0f), 0.0f, 0.5f}, 0.8f, 1.0f},            // dielectric, mostly diffuse
    {{{0.9f, 0.6f, 0.3f}, 1.0f, 0.4f}, 0.5f, -1.0f},   // metal, normal given on the far side
    {{vec3(0.7f), 0.5f, 1.0f}, 0.15f, 1.0f},           // half metal, grazing
    {{{0.2f, 0.5f, 0.8f}, 0.2f, 0.7f}, 1.0f, 1.0f},    // coloured, head-on
};

constexpr int kChiSquareDraws = 200000;

TEST(Bsdf, ChiSquareSampleMatchesPdf) {
  // H0: sample() draws wi (or nothing) with the density pdf(). Per case: 200000 draws from Philox
  // stream 20 + case, 20 x 40 cells plus the miss cell, expectations by quadrature of pdf(), cells
  // under 5 pooled, any draw in a cell of expectation 0 (e.g. below the surface) fails. Family-wise
  // alpha 0.01 over the cases (Sidak).
  const double alpha = trs_test::sidak_alpha(0.01, kChiSquareCases.size());
  for (std::uint32_t c = 0; c < kChiSquareCases.size(); ++c) {
    const ChiSquareCase& test = kChiSquareCases[c];
    const Bsdf bsdf(test.params, vec3(0.0f, 0.0f, test.normal_z));
    const auto result = chi_square(bsdf, bsdf, spherical(test.cos_wo, 0.0f), 20 + c, kChiSquareDraws);
    EXPECT_GE(result.dof, 50.0) << "case " << c << ": too few cells to have power";
    EXPECT_TRUE(result.passes(alpha)) << "case " << c << ": " << result.describe();
  }
}

TEST(Bsdf, ChiSquareRejectsWrongPdf) {
  // The same check has power: the draws that pass above for the metal case (same stream), held
  // against the pdf of alpha = roughness instead of roughness^2 (a Bsdf of roughness
  // sqrt(roughness)), must be rejected at alpha 0.01.
  const ChiSquareCase& test = kChiSquareCases[1];
  SurfaceParams wrong = test.params;
  wrong.roughness = std::sqrt(wrong.roughness);
  const vec3 normal(0.0f, 0.0f, test.normal_z);
  const auto result = chi_square(Bsdf(test.params, normal), Bsdf(wrong, normal), spherical(test.cos_wo, 0.0f), 21,
                                 kChiSquareDraws);
  EXPECT_FALSE(result.passes(0.01)) << result.describe();
}

}  // namespace
}  // namespace tracer
