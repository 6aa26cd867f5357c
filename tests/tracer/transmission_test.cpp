// Light through transmissive surfaces (KHR_materials_transmission, _volume, _clearcoat), on the
// analytic bench of quad_over_plane.h: an emissive quad with a random texture above a plane.
//
// Hypothesis: every estimator stays unbiased where light crosses surfaces. A smooth thin pane
// between the emitter and the plane: next-event estimation draws the emitter through it, carrying
// its straight-through transmittance, and BSDF sampling passes through it, each weighed against
// the other; every strategy's mean must equal the quadrature with the pane's transmittance in it.
// Test as in analytic_test.cpp: each channel within 4 standard errors (400 independent frames of
// 500 paths, fixed seeds) plus 1e-4 relative for the quadrature. A deliberately wrong strategy
// must fail the same check through the pane.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "quad_over_plane.h"

namespace {

using namespace tracer;
using namespace trs_test;

/// A thin, smooth, transmissive material of base colour `tint`.
Material pane(glm::vec3 tint, float specular = 1.0f) {
  Material m = matte(tint, 0.0f);
  m.transmission.factor = 1.0f;
  m.specular.factor = specular;
  return m;
}

/// The bench with a horizontal pane of `material` over [x0, x1] x [y0, y1] at height z.
QuadOverPlane bench_with_pane(const Material& material, float z, glm::vec2 lo = glm::vec2(-4.0f),
                              glm::vec2 hi = glm::vec2(4.0f)) {
  return QuadOverPlane(kCpuSampler, [&](Scene& scene) {
    const std::uint32_t m = add_material(scene, material);
    add_quad(scene, {lo.x, lo.y, z}, {hi.x, lo.y, z}, {hi.x, hi.y, z}, {lo.x, hi.y, z}, m);
  });
}

/// The pane's straight-through transmittance at cosine mu: its tint times 1 - Schlick's F of
/// index 1.5, for a thin smooth surface without coat or sheen (bsdf.h).
glm::dvec3 pane_transmittance(glm::vec3 tint, double mu) {
  const double f = 0.04 + 0.96 * std::pow(1.0 - mu, 5.0);
  return glm::dvec3(tint) * (1.0 - f);
}

TEST(Transmission, EveryStrategyDrawsTheEmitterThroughASmoothPane) {
  const glm::vec3 tint(0.9f, 0.6f, 0.8f);
  // Wide enough to cover every way from the plane's point to the emitter.
  const QuadOverPlane bench = bench_with_pane(pane(tint), 0.6f);
  // Each way from the point to the emitter crosses the horizontal pane at the cosine of its
  // own direction.
  const glm::dvec3 expected = bench.integrate_weighted(
      [&](double u, double v) {
        return bench.radiance_at(std::uint32_t(u * kTexWidth), std::uint32_t(v * kTexHeight));
      },
      kTexWidth, kTexHeight, [&](glm::vec3 wi) { return pane_transmittance(tint, wi.z); });
  ASSERT_GT(expected.g, 0.0);
  for (const std::string& kind : trs_test::every_strategy()) {
    auto s = make_light_strategy(*bench.emitters, options(kind));
    const Estimate e = bench.run(*s, 11);
    EXPECT_TRUE(agrees(e, expected, kSigmas, kQuadratureSlack)) << kind << "\n" << describe(e, expected);
  }
  // The check has power here: lights drawn by one strategy and weighed by another's density.
  DrawnByOneWeighedByAnother wrong(strategy(*bench.emitters, "uniform"),
                                   strategy(*bench.emitters, "power"));
  const Estimate e = bench.run(wrong, 12);
  EXPECT_FALSE(agrees(e, expected, kSigmas, kQuadratureSlack)) << describe(e, expected);
}

TEST(Transmission, ACameraRaySeesThroughAPaneWithoutScattering) {
  // A pane without a specular layer (specular 0: no reflection) and fully transmissive lets the
  // camera's ray straight through with probability 1 and its tint as weight: the plane's
  // radiance times the tint, the path's depth unchanged (direct light still found below it).
  // The pane covers only where the camera's ray crosses z = 0.2, (0.33, -0.02), not the ways
  // from the plane's point to the emitter (x < 0.18 at that height).
  const glm::vec3 tint(0.5f, 0.7f, 0.9f);
  const QuadOverPlane bench = bench_with_pane(pane(tint, 0.0f), 0.2f, {0.25f, -0.1f}, {0.42f, 0.07f});
  const glm::dvec3 expected = glm::dvec3(tint) * bench.expected();
  auto s = make_light_strategy(*bench.emitters, options("power"));
  const Estimate e = bench.run(*s, 13);
  EXPECT_TRUE(agrees(e, expected, kSigmas, kQuadratureSlack)) << describe(e, expected);
}

TEST(Transmission, AVolumeAbsorbsAlongTheWayInside) {
  // A slab of index 1 (no bending, no reflection head-on) absorbing by Beer-Lambert, 0.4 thick,
  // between the camera and the emitter, seen head-on: the emitter's texel times
  // attenuation_color^(0.4 / attenuation_distance), and times the two interfaces' transmission,
  // 1 up to the GGX's masking at alpha 1e-3 (under 1e-4 here). Paths of depth 3: enter, leave,
  // see the emitter. 4 standard errors plus 1e-3 for the masking.
  Material glass = matte(glm::vec3(1.0f), 0.0f);
  glass.transmission.factor = 1.0f;
  glass.ior = 1.0f;
  glass.volume = Volume{{0.5f, 0.8f, 0.9f}, 0.25f};
  QuadOverPlane bench(kCpuSampler, [&](Scene& scene) {
    const std::uint32_t m = add_material(scene, glass);
    // A box from z 0.3 to 0.7, its faces outward (counter-clockwise seen from outside).
    const float lo = 0.3f, hi = 0.7f, w = 3.0f;
    add_quad(scene, {-w, -w, hi}, {w, -w, hi}, {w, w, hi}, {-w, w, hi}, m);
    add_quad(scene, {-w, -w, lo}, {-w, w, lo}, {w, w, lo}, {w, -w, lo}, m);
    add_quad(scene, {-w, -w, lo}, {w, -w, lo}, {w, -w, hi}, {-w, -w, hi}, m);
    add_quad(scene, {w, w, lo}, {-w, w, lo}, {-w, w, hi}, {w, w, hi}, m);
    add_quad(scene, {w, -w, lo}, {w, w, lo}, {w, w, hi}, {w, -w, hi}, m);
    add_quad(scene, {-w, w, lo}, {-w, -w, lo}, {-w, -w, hi}, {-w, w, hi}, m);
  });
  // Straight up from below the slab to the centre of the emitter's first lit texel (i, j): u =
  // (i + 0.5) / 8 along +y, v = (j + 0.5) / 4 along +x (quad_over_plane.h).
  std::uint32_t i = 0, j = 0;
  while (bench.radiance_at(i, j).r <= 0.0) {
    if (++i == kTexWidth) i = 0, ++j;
  }
  const glm::vec3 target(float(-0.5 + (j + 0.5) / kTexHeight), float(-0.5 + (i + 0.5) / kTexWidth), 1.0f);
  const Ray up{target - glm::vec3(0.0f, 0.0f, 0.9f), glm::vec3(0.0f, 0.0f, 1.0f)};
  const glm::dvec3 absorbed = glm::pow(glm::dvec3(0.5, 0.8, 0.9), glm::dvec3(0.4 / 0.25));
  const glm::dvec3 expected = bench.radiance_at(i, j) * absorbed;
  auto s = make_light_strategy(*bench.emitters, options("power"));
  const Estimate e = estimate_radiance(bench.scene, *bench.geometry, *bench.emitters, *s, up, 3, 50, 200, 14);
  EXPECT_TRUE(agrees(e, expected, kSigmas, 1e-3)) << describe(e, expected);
}

TEST(Transmission, AClearcoatDimsTheEmissionUnderIt) {
  // KHR_materials_clearcoat: emission times 1 - clearcoat F(|V.N|), F of index 1.5: 1 - 0.7 x
  // 0.04 head-on; towards grazing, 1 - 0.7.
  QuadOverPlane bench(kCpuSampler, [](Scene& scene) { scene.materials[0].clearcoat.factor = 0.7f; });
  const glm::vec3 down(0.0f, 0.0f, -1.0f);
  const glm::vec3 plain = bench.emitters->emission(0, 0.3f, 0.3f);
  ASSERT_GT(plain.r, 0.0f);
  const glm::vec3 head_on = bench.emitters->radiance(0, 0.3f, 0.3f, down);
  EXPECT_NEAR(head_on.r, plain.r * (1.0f - 0.7f * 0.04f), 1e-5f * plain.r);
  const glm::vec3 grazing = bench.emitters->radiance(0, 0.3f, 0.3f, glm::normalize(glm::vec3(1.0f, 0.0f, -1e-4f)));
  EXPECT_NEAR(grazing.r, plain.r * 0.3f, 1e-3f * plain.r);
}

}  // namespace
