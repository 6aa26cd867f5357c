// Punctual lights (KHR_lights_punctual) beside an emissive quad: the radiance the plane under the
// quad reflects along one ray, direct lighting only, against the quad's quadrature plus each
// punctual light's analytic contribution f(wo, wi) I falloff / d^2 (E for a directional light).
//
// Hypothesis: every strategy, with the punctual lights beside the triangles, is unbiased.
// Test: each channel's mean lies within 4 standard errors of the expected value (plus 1e-4
// relative for the quadrature), 400 frames of 500 paths, seeds fixed, as analytic_test.cpp. The
// same estimates must miss a wrong falloff (1 / d, or a spot's ramp not squared) by the same
// test, so that the check can fail.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "quad_over_plane.h"

namespace {

using namespace tracer;
using namespace trs_test;

PunctualLight point_light(glm::vec3 position, glm::vec3 intensity) {
  PunctualLight light;
  light.kind = PunctualLight::Kind::point;
  light.position = position;
  light.intensity = intensity;
  return light;
}

/// A spot at `position` whose axis makes `off_axis` radians with the way to `target`.
PunctualLight spot_light(glm::vec3 position, glm::vec3 target, float off_axis, float inner, float outer,
                         glm::vec3 intensity) {
  PunctualLight light = point_light(position, intensity);
  light.kind = PunctualLight::Kind::spot;
  const glm::vec3 to_target = glm::normalize(target - position);
  // Tilt the axis about a direction orthogonal to the way to the target.
  const glm::vec3 side = glm::normalize(glm::cross(to_target, glm::vec3(0, 0, 1)));
  const glm::vec3 up = glm::cross(side, to_target);
  light.direction = std::cos(off_axis) * to_target + std::sin(off_axis) * up;
  light.cos_inner = std::cos(inner);
  light.cos_outer = std::cos(outer);
  return light;
}

PunctualLight sun(glm::vec3 towards_sun, glm::vec3 irradiance) {
  PunctualLight light;
  light.kind = PunctualLight::Kind::directional;
  light.direction = -glm::normalize(towards_sun);
  light.intensity = irradiance;
  return light;
}

/// Where the bench's ray meets the plane (QuadOverPlane::point), which the spots aim near.
const glm::vec3 kBenchPoint{0.1f, 0.15f, 0.0f};

/// The quad over the plane with punctual lights beside it; `emitting`: whether the quad emits.
struct WithPunctual {
  QuadOverPlane bench;
  explicit WithPunctual(std::vector<PunctualLight> lights, bool emitting = true) {
    if (bench.point != kBenchPoint) throw std::logic_error("the spots aim at another point than the bench's");
    bench.scene.lights = std::move(lights);
    if (!emitting) bench.scene.materials[0].emissive_factor = glm::vec3(0.0f);
    bench.emitters = std::make_unique<Emitters>(bench.scene, kCpuSampler);
  }
};

/// How a light's contribution falls off, written out from KHR_lights_punctual.
enum class Falloff { gltf, one_over_distance, linear_spot_ramp };

/// f(wo, wi) times the irradiance light `light` brings to the bench's point, by `falloff`.
glm::dvec3 contribution(const QuadOverPlane& bench, const PunctualLight& light, Falloff falloff) {
  const Material& m = bench.scene.materials[1];
  const Bsdf bsdf({m.base_color, m.metallic, m.roughness}, {0, 0, 1});
  const glm::vec3 wo = glm::normalize(bench.eye - bench.point);
  if (light.kind == PunctualLight::Kind::directional)
    return glm::dvec3(bsdf.eval(wo, -light.direction)) * glm::dvec3(light.intensity);
  const glm::dvec3 d = glm::dvec3(light.position) - glm::dvec3(bench.point);
  const double distance = glm::length(d);
  double spot = 1.0;
  if (light.kind == PunctualLight::Kind::spot) {
    const double cos_theta = glm::dot(-d / distance, glm::dvec3(light.direction));
    const double t = std::clamp((cos_theta - light.cos_outer) / (double(light.cos_inner) - light.cos_outer), 0.0, 1.0);
    spot = falloff == Falloff::linear_spot_ramp ? t : t * t;
  }
  const double attenuation = falloff == Falloff::one_over_distance ? 1.0 / distance : 1.0 / (distance * distance);
  return glm::dvec3(bsdf.eval(wo, glm::vec3(d / distance))) * glm::dvec3(light.intensity) * (spot * attenuation);
}

/// Every strategy's estimate, and ris's over each of its sources, must agree with the quad's
/// quadrature plus the lights' contributions; with `wrong`, none may agree with it instead.
void expect_every_strategy_sums(const WithPunctual& scene, bool emitting, std::optional<Falloff> wrong = {}) {
  const QuadOverPlane& bench = scene.bench;
  glm::dvec3 expected = emitting ? bench.expected() : glm::dvec3(0.0), miss = expected;
  for (const PunctualLight& light : bench.scene.lights) {
    expected += contribution(bench, light, Falloff::gltf);
    if (wrong) miss += contribution(bench, light, *wrong);
  }
  ASSERT_GT(expected.g, 0.0);
  for (const std::string& kind : trs_test::every_strategy()) {
    const StrategyOptions o = options(kind);
    auto s = make_light_strategy(*bench.emitters, o);
    const Estimate e = bench.run(*s, 11);
    EXPECT_TRUE(agrees(e, expected, kSigmas, kQuadratureSlack)) << kind << "\n" << describe(e, expected);
    if (wrong) EXPECT_FALSE(agrees(e, miss, kSigmas, kQuadratureSlack)) << kind << " accepts a wrong falloff";
  }
}

const glm::vec3 kPointPosition{1.5f, 0.8f, 0.8f};  // below the quad: nothing blocks it

TEST(PunctualLights, APointLightGivesIntensityOverDistanceSquared) {
  const WithPunctual scene({point_light(kPointPosition, {1.5f, 1.2f, 0.9f})});
  expect_every_strategy_sums(scene, true, Falloff::one_over_distance);
}

TEST(PunctualLights, ASpotInsideItsInnerConeShinesFully) {
  const WithPunctual scene({spot_light({-1.2f, 0.6f, 0.7f}, kBenchPoint, 0.1f, 0.3f, 0.6f, {2.0f, 1.0f, 1.5f})});
  expect_every_strategy_sums(scene, true);
}

TEST(PunctualLights, ASpotBetweenItsConesFallsOffAsTheSquaredRamp) {
  const WithPunctual scene({spot_light({-1.2f, 0.6f, 0.7f}, kBenchPoint, 0.45f, 0.3f, 0.6f, {2.0f, 1.0f, 1.5f})});
  expect_every_strategy_sums(scene, true, Falloff::linear_spot_ramp);
}

TEST(PunctualLights, ASpotOutsideItsOuterConeLightsNothing) {
  const WithPunctual scene({spot_light({-1.2f, 0.6f, 0.7f}, kBenchPoint, 0.7f, 0.3f, 0.6f, {2.0f, 1.0f, 1.5f})});
  EXPECT_EQ(contribution(scene.bench, scene.bench.scene.lights[0], Falloff::gltf), glm::dvec3(0.0));
  expect_every_strategy_sums(scene, true);
}

TEST(PunctualLights, ASunGivesItsIrradiance) {
  const WithPunctual scene({sun({1.0f, 0.2f, 0.6f}, {0.6f, 0.5f, 0.4f})});
  expect_every_strategy_sums(scene, true);
}

// Every kind at once, and the same lights with the quad dark: no emissive triangle at all.
TEST(PunctualLights, AllKindsTogetherWithAndWithoutEmissiveTriangles) {
  const std::vector<PunctualLight> lights = {
      point_light(kPointPosition, {1.5f, 1.2f, 0.9f}),
      spot_light({-1.2f, 0.6f, 0.7f}, kBenchPoint, 0.45f, 0.3f, 0.6f, {2.0f, 1.0f, 1.5f}),
      sun({1.0f, 0.2f, 0.6f}, {0.6f, 0.5f, 0.4f})};
  expect_every_strategy_sums(WithPunctual(lights, true), true);
  const WithPunctual dark(lights, false);
  EXPECT_EQ(dark.bench.emitters->count(), 0u);
  expect_every_strategy_sums(dark, false);
}

// glTF's range: the window max(min(1 - (d / range)^4, 1), 0) on top of 1 / d^2.
TEST(PunctualLights, RangeWindowsTheFalloff) {
  PunctualLight light = point_light(kPointPosition, {1.0f, 1.0f, 1.0f});
  light.range = 2.0f;
  EXPECT_FLOAT_EQ(PunctualLights::range_window(light, 1.0f), 1.0f - 1.0f / 16.0f);
  EXPECT_FLOAT_EQ(PunctualLights::range_window(light, 2.5f), 0.0f);
  light.range = 0.0f;
  EXPECT_FLOAT_EQ(PunctualLights::range_window(light, 1e6f), 1.0f);
}

}  // namespace
