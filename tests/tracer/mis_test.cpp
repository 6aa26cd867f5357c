// MIS: at a shading point, a light sample's weight and the weight the same path gets when BSDF
// sampling finds it sum to one, for every strategy. That holds only if the density a light
// sample reports (mis_pdf, in solid angle) is the density pdf() gives at a BSDF hit on the same
// point, seen from the shading point, and if pdf() is a normalised area density over the lights. `ris` weighs the light it keeps with that
// same mis_pdf (PathTracer::light_sample), whichever candidate it keeps. With punctual lights
// beside the emitters, their delta samples take no part in MIS (a weight of one), and the
// triangles' pdf() integrates to the probability of drawing a triangle rather than one of them.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "quad_over_plane.h"
#include "registered_strategies.h"
#include "scene_builder.h"
#include "tracer/bsdf.h"
#include "tracer/emitters.h"
#include "tracer/light_strategy.h"
#include "support/chi_square.h"
#include "tracer/path_tracer.h"

namespace {

using namespace tracer;

/// Two emissive quads of different textures and strengths, one tilted.
Scene two_emitters() {
  Scene scene;
  Material a;
  a.emissive_factor = glm::vec3(1.0f);
  a.emissive_texture.texture = trs_test::add_random_texture(scene, 16, 8, 0.5, 21);
  Material b = a;
  b.emissive_texture.texture = trs_test::add_random_texture(scene, 5, 7, 0.2, 22);
  b.emissive_strength = 4.0f;
  const std::uint32_t ma = trs_test::add_material(scene, a), mb = trs_test::add_material(scene, b);
  trs_test::add_quad(scene, {-1, -1, 2}, {-1, 1, 2}, {1, 1, 2}, {1, -1, 2}, ma);
  trs_test::add_quad(scene, {2, -1, 0}, {2, -1, 1}, {2, 1, 1.5f}, {2, 1, 0}, mb);
  return scene;
}

/// The two quads with a point light, a spot and a sun beside them.
Scene two_emitters_and_punctual_lights() {
  Scene scene = two_emitters();
  PunctualLight point, spot, sun;
  point.position = glm::vec3(-1.5f, 0.5f, 1.0f);
  point.intensity = glm::vec3(3.0f, 2.0f, 1.0f);
  spot.kind = PunctualLight::Kind::spot;
  spot.position = glm::vec3(0.5f, -1.5f, 1.2f);
  spot.direction = glm::normalize(glm::vec3(-0.2f, 1.0f, -1.0f));
  spot.intensity = glm::vec3(5.0f);
  spot.cos_inner = std::cos(0.3f);
  spot.cos_outer = std::cos(0.7f);
  sun.kind = PunctualLight::Kind::directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
  sun.intensity = glm::vec3(0.5f);
  scene.lights = {point, spot, sun};
  return scene;
}

StrategyOptions options(const std::string& kind, TreeImportance importance = TreeImportance::pbrt) {
  StrategyOptions options;
  options.kind = kind;
  options.lights = 1e4;
  options.tree.importance = importance;
  return options;
}

/// Every registered strategy; those that pick by the tree with each of its importances.
std::vector<StrategyOptions> every_strategy() {
  std::vector<StrategyOptions> all;
  for (const std::string& name : trs_test::every_strategy()) {
    all.push_back(options(name));
    if (picks_by_tree(all.back())) all.push_back(options(name, TreeImportance::cycles));
  }
  return all;
}

std::string name(const StrategyOptions& o) {
  return picks_by_tree(o) ? o.kind + ", " + to_string(o.tree.importance) : o.kind;
}

TEST(Mis, LightAndBsdfWeightsSumToOne) {
  for (const Scene& scene : {two_emitters(), two_emitters_and_punctual_lights()}) {
    Emitters emitters(scene, trs_test::kCpuSampler);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 x(0.2f, 0.1f, 0.0f), n(0, 0, 1), wo = glm::normalize(glm::vec3(0.3f, -0.2f, 1));
    const ShadingPoint at{x, n};
    const Bsdf bsdf({glm::vec3(0.7f), 0.3f, 0.4f}, n);
    for (const StrategyOptions& o : every_strategy()) {
      auto strategy = make_light_strategy(emitters, o);
      strategy->begin_pass(0);
      int checked = 0;
      for (int i = 0; i < 2000; ++i) {
        LightRandom random;
        for (auto& word : random) word = std::uint32_t(rng());
        const auto s = strategy->sample(random, at);
        ASSERT_TRUE(s.has_value() || !scene.lights.empty());
        if (!s) continue;  // a spot that does not shine here
        if (s->delta) {  // no BSDF sample finds it
          ASSERT_EQ(s->mis_pdf, 0.0f) << name(o);
          continue;
        }
        const glm::vec3 d = s->position - x;
        const float r = glm::length(d);
        const glm::vec3 wi = d / r;
        const float cos_light = glm::dot(-wi, s->normal);
        // The sample holds what the emitters give at its point, seen from `at`, bit for bit.
        ASSERT_EQ(s->position, emitters.position(s->light, s->b1, s->b2)) << name(o);
        ASSERT_EQ(s->normal, emitters.normal(s->light)) << name(o);
        ASSERT_EQ(s->wi, wi) << name(o);
        ASSERT_EQ(s->distance, r) << name(o);
        ASSERT_EQ(s->li, emitters.radiance(s->light, s->b1, s->b2, -wi)) << name(o);
        // The light sample's weight, and the weight emitted() gives a BSDF hit there: equal but
        // for rounding where punctual lights are chosen beside the triangles (their probability
        // multiplies the sample's solid-angle density, and pdf()'s area density).
        const float hit_pdf = solid_angle_density(strategy->pdf(s->light, s->b1, s->b2, at), r, cos_light);
        ASSERT_NEAR(s->mis_pdf, hit_pdf, 1e-6f * hit_pdf) << name(o);
        const float bsdf_pdf = bsdf.pdf(wo, wi);
        if (bsdf_pdf <= 0.0f || cos_light <= 0.0f) continue;  // only one technique reaches it
        EXPECT_NEAR(power_heuristic(s->mis_pdf, bsdf_pdf) + power_heuristic(bsdf_pdf, hit_pdf), 1.0f, 1e-5f);
        ++checked;
      }
      EXPECT_GT(checked, 100) << name(o);
    }
  }
}

// pdf() integrates to one over the lights: a Monte Carlo integral by uniform points on each
// light, 20,000 per light (seed 5), within 1% (the density is piecewise constant with a ratio of
// at most 20 between texels, or for the tree smooth over each light: the relative standard error
// is below 0.3%). With punctual lights, to one less the share of 20,000 draws that pick one
// (seed 6; its standard error is below 0.4%), within 1.5%.
TEST(Mis, PdfIsANormalisedAreaDensity) {
  for (const Scene& scene : {two_emitters(), two_emitters_and_punctual_lights()}) {
    Emitters emitters(scene, trs_test::kCpuSampler);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const ShadingPoint from{glm::vec3(0.2f, 0.1f, 0.0f), glm::vec3(0, 0, 1)};
    for (const StrategyOptions& o : every_strategy()) {
      if (find_strategy(o.kind)->resamples) continue;  // ris is its source under another name
      auto strategy = make_light_strategy(emitters, o);
      double integral = 0.0;
      constexpr int kPoints = 20000;
      for (std::uint32_t light = 0; light < emitters.count(); ++light) {
        double sum = 0.0;
        for (int i = 0; i < kPoints; ++i) {
          float b1 = u(rng), b2 = u(rng);
          if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
          sum += strategy->pdf(light, b1, b2, from);
        }
        integral += sum / kPoints * emitters.area(light);
      }
      double punctual = 0.0;
      if (!scene.lights.empty()) {
        std::mt19937 words(6);
        strategy->begin_pass(0);
        for (int i = 0; i < kPoints; ++i) {
          LightRandom random;
          for (auto& word : random) word = std::uint32_t(words());
          const auto s = strategy->sample(random, from);
          punctual += s && s->delta ? 1.0 / kPoints : 0.0;
        }
        EXPECT_GT(punctual, 0.01) << name(o);
      }
      EXPECT_NEAR(integral + punctual, 1.0, scene.lights.empty() ? 0.01 : 0.015) << name(o);
    }
  }
}

/// Cells of a light: a 4 x 4 grid over (s, t) = ((b1 + b2)^2, b2 / (b1 + b2)), which maps the
/// triangle onto the unit square preserving area, so every cell is a sixteenth of the light.
constexpr int kGrid = 4;

std::size_t cell(std::uint32_t light, float b1, float b2) {
  const float sum = b1 + b2;
  const float s = sum * sum, t = sum > 0.0f ? b2 / sum : 0.0f;
  const auto i = std::min(int(s * kGrid), kGrid - 1), j = std::min(int(t * kGrid), kGrid - 1);
  return std::size_t(light) * kGrid * kGrid + std::size_t(i * kGrid + j);
}

/// The probability of each cell by the strategy's pdf(): the midpoint rule on 64 x 64 points of
/// each cell's (s, t) square.
std::vector<double> cell_probabilities(const LightStrategy& strategy, const Emitters& emitters, const ShadingPoint& at) {
  constexpr int kPoints = 64 * kGrid;
  std::vector<double> p(emitters.count() * kGrid * kGrid, 0.0);
  for (std::uint32_t light = 0; light < emitters.count(); ++light) {
    const double point_area = double(emitters.area(light)) / (kPoints * kPoints);
    for (int a = 0; a < kPoints; ++a)
      for (int b = 0; b < kPoints; ++b) {
        const float s = (float(a) + 0.5f) / kPoints, t = (float(b) + 0.5f) / kPoints, r = std::sqrt(s);
        const float b1 = r * (1.0f - t), b2 = r * t;
        p[cell(light, b1, b2)] += strategy.pdf(light, b1, b2, at) * point_area;
      }
  }
  return p;
}

/// The cells of `draws` light samples of `strategy` at `at`, words from seed `seed`.
std::vector<double> cell_counts(LightStrategy& strategy, const Emitters& emitters, const ShadingPoint& at,
                                int draws, unsigned seed) {
  std::vector<double> counts(emitters.count() * kGrid * kGrid, 0.0);
  std::mt19937 rng(seed);
  strategy.begin_pass(seed);
  for (int i = 0; i < draws; ++i) {
    LightRandom random;
    for (auto& word : random) word = std::uint32_t(rng());
    if (const auto s = strategy.sample(random, at)) counts[cell(s->light, s->b1, s->b2)] += 1.0;
  }
  return counts;
}

// The light samples follow the density pdf() reports: a chi-square test over 16 cells of each
// light, expected counts from the midpoint rule on pdf() (64 x 64 points a cell: its error, where
// texels cut a cell, is well below the counts' own), 40,000 draws, seed 7, at alpha 0.01 Šidák-
// corrected over the strategies. A strategy that draws a set of point lights each pass (`trs`, and
// `ris` over it) draws from 10^6 of them, so that the set's own sampling error is negligible. Shown to reject a strategy that draws by area and reports the density of `power`.
TEST(Mis, LightSamplesFollowTheirPdf) {
  const Scene scene = two_emitters();
  Emitters emitters(scene, trs_test::kCpuSampler);
  const ShadingPoint at{glm::vec3(0.2f, 0.1f, 0.0f), glm::vec3(0, 0, 1)};
  constexpr int kDraws = 40000;
  const std::vector<StrategyOptions> strategies = every_strategy();
  const double alpha = trs_test::sidak_alpha(0.01, strategies.size() + 1);
  const auto test = [&](LightStrategy& strategy) {
    const std::vector<double> observed = cell_counts(strategy, emitters, at, kDraws, 7);
    std::vector<double> expected = cell_probabilities(strategy, emitters, at);
    for (double& e : expected) e *= kDraws;
    return trs_test::chi_square_test(observed, expected, 0);
  };
  for (StrategyOptions o : strategies) {
    if (draws_point_lights(o)) o.lights = 1e6;  // the set's own error negligible against the draws'
    auto strategy = make_light_strategy(emitters, o);
    const trs_test::ChiSquareResult result = test(*strategy);
    EXPECT_TRUE(result.passes(alpha)) << name(o) << "\n" << result.describe();
  }
  trs_test::DrawnByOneWeighedByAnother wrong(make_light_strategy(emitters, options("uniform")),
                                             make_light_strategy(emitters, options("power")));
  EXPECT_FALSE(test(wrong).passes(alpha)) << "a sampler whose draws do not follow its pdf passes";
}

}  // namespace
