// A light of each kind (tracer/include/tracer/light.h), and the choice that takes the emissive
// triangles as one light beside the punctual lights (light_choice.h).
//
// Kinds. Each light answers its kind; only punctual lights are delta lights.
//
// Solid angle. A point of a triangle seen from a shading point: the density its sample divides
// by, and the one the light gives again for the same point found by a BSDF sample (pdf_li), are
// one number bit for bit, the area density times d^2 / |cos theta_l|; a deliberately wrong
// conversion (without the cosine) differs.
//
// Grouped choice. Hypothesis: the probability it reports for the triangles as a whole and for
// each punctual light is the probability that it picks them, each in proportion to its power
// (Light::power). Test: 10^6 picks (seed 1), Pearson chi-square of the counts against 10^6 times
// the pmf, alpha 0.01; the same counts against equal shares must fail.

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <vector>

#include "scene_builder.h"
#include "strategies/light_choice.h"
#include "support/chi_square.h"
#include "tracer/emitters.h"

namespace {

using namespace tracer;

/// Two emissive quads (one two-sided) and a point, a spot and a directional light.
Scene lit_scene() {
  Scene scene;
  Material one_sided;
  one_sided.emissive_factor = glm::vec3(1.0f);
  one_sided.emissive_strength = 3.0f;
  Material two_sided = one_sided;
  two_sided.double_sided = true;
  trs_test::add_quad(scene, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, trs_test::add_material(scene, one_sided));
  trs_test::add_quad(scene, {0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {0, 1, 1}, trs_test::add_material(scene, two_sided));
  scene.lights.push_back({.kind = PunctualLight::Kind::point, .position = {0, 0, 3}, .intensity = glm::vec3(5.0f)});
  scene.lights.push_back({.kind = PunctualLight::Kind::spot,
                          .position = {1, 1, 3},
                          .direction = {0, 0, -1},
                          .intensity = glm::vec3(8.0f),
                          .cos_inner = 0.9f,
                          .cos_outer = 0.7f});
  scene.lights.push_back({.kind = PunctualLight::Kind::directional, .direction = {0, 0, -1}, .intensity = glm::vec3(0.5f)});
  return scene;
}

LightRandom random_words(std::mt19937& rng) {
  LightRandom random;
  for (auto& word : random) word = std::uint32_t(rng());
  return random;
}

TEST(Light, AnswersItsKind) {
  Scene scene = lit_scene();
  const Emitters emitters(scene, trs_test::kCpuSampler);
  ASSERT_EQ(emitters.count(), 4u);
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(emitters.light(i).kind(), Light::Kind::triangle);
    EXPECT_FALSE(emitters.light(i).delta());
  }
  EXPECT_EQ(emitters.light(4).kind(), Light::Kind::point);
  EXPECT_EQ(emitters.light(5).kind(), Light::Kind::spot);
  EXPECT_EQ(emitters.light(6).kind(), Light::Kind::directional);
  for (std::uint32_t i = 4; i < 7; ++i) EXPECT_TRUE(emitters.light(i).delta());
}

TEST(Light, SampleAndPdfLiAgreeInSolidAngle) {
  Scene scene = lit_scene();
  const Emitters emitters(scene, trs_test::kCpuSampler);
  const ShadingPoint at{glm::vec3(0.4f, 0.3f, 2.2f), glm::vec3(0.0f, 0.0f, -1.0f)};
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int checked = 0, wrong_differs = 0;
  for (int i = 0; i < 1000; ++i) {
    const Light light = emitters.light(std::uint32_t(i % 4));
    const float b1 = unit(rng), b2 = (1.0f - b1) * unit(rng);
    const float area_density = 0.1f + unit(rng);
    const std::optional<LightLiSample> s = light.sample_li(light.point(b1, b2, area_density, area_density), at);
    ASSERT_TRUE(s);
    const float pdf = light.pdf_li(area_density, -s->wi, s->distance);
    EXPECT_EQ(s->pdf, pdf);
    EXPECT_EQ(s->mis_pdf, pdf);
    const float cos_light = std::abs(glm::dot(s->wi, emitters.normal(light.index())));
    EXPECT_NEAR(pdf, area_density * s->distance * s->distance / cos_light, 1e-5f * pdf);
    wrong_differs += area_density * s->distance * s->distance != pdf;
    ++checked;
  }
  EXPECT_EQ(checked, 1000);
  EXPECT_GT(wrong_differs, 900) << "a conversion without the cosine should not pass";
}

TEST(LightChoice, GroupedPowerChoicePicksEachWithItsPowerShare) {
  Scene scene = lit_scene();
  const Emitters emitters(scene, trs_test::kCpuSampler);
  const auto choice = make_grouped_power_choice(emitters, true);
  const ShadingPoint at{glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)};
  // Cells: the triangles, then each punctual light.
  const std::uint32_t triangles = emitters.count(), cells = 1 + emitters.punctual().count();
  double total = 0.0, triangle_power = 0.0;
  for (std::uint32_t l = 0; l < triangles + cells - 1; ++l) total += emitters.light(l).power();
  for (std::uint32_t l = 0; l < triangles; ++l) triangle_power += emitters.light(l).power();
  for (std::uint32_t l = 0; l < triangles; ++l) EXPECT_NEAR(choice->pmf(l, at), triangle_power / total, 1e-12);
  std::vector<double> expected(cells), equal(cells, 1e6 / cells), observed(cells, 0.0);
  expected[0] = choice->pmf(0, at) * 1e6;
  for (std::uint32_t c = 1; c < cells; ++c) {
    expected[c] = choice->pmf(triangles + c - 1, at) * 1e6;
    EXPECT_NEAR(expected[c], emitters.light(triangles + c - 1).power() / total * 1e6, 1e-6);
  }
  std::mt19937 rng(1);
  for (int i = 0; i < 1000000; ++i) {
    const std::optional<LightPick> pick = choice->pick(random_words(rng), at);
    ASSERT_TRUE(pick);
    const std::uint32_t cell = pick->light == kEveryTriangle ? 0 : pick->light - triangles + 1;
    ASSERT_LT(cell, cells);
    EXPECT_EQ(pick->pmf, cell == 0 ? choice->pmf(0, at) : choice->pmf(pick->light, at));
    observed[cell] += 1.0;
  }
  const trs_test::ChiSquareResult result = trs_test::chi_square_test(observed, expected);
  EXPECT_TRUE(result.passes(0.01)) << result.describe();
  EXPECT_FALSE(trs_test::chi_square_test(observed, equal).passes(0.01)) << "equal shares should fail";
}

TEST(LightChoice, GroupedPowerChoiceWithoutTrianglesPicksOnlyPunctualLights) {
  Scene scene = lit_scene();
  const Emitters emitters(scene, trs_test::kCpuSampler);
  const auto choice = make_grouped_power_choice(emitters, false);
  const ShadingPoint at{glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)};
  EXPECT_EQ(choice->pmf(0, at), 0.0);
  std::mt19937 rng(1);
  for (int i = 0; i < 10000; ++i) {
    const std::optional<LightPick> pick = choice->pick(random_words(rng), at);
    ASSERT_TRUE(pick);
    EXPECT_GE(pick->light, emitters.count());
    EXPECT_NE(pick->light, kEveryTriangle);
  }
}

}  // namespace
