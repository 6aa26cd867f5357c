// A furnace: a closed cube whose inside emits radiance 1 everywhere. Seen from inside, a wall
// returns its emission plus what it reflects of the uniform emission around it:
// L = 1 + A(wo) after one bounce, with A the BSDF's directional albedo, found here by quadrature
// of Bsdf::eval over the hemisphere. Light sampling and BSDF sampling both see the whole
// emitter, so this checks that their MIS combination counts every direction exactly once.
//
// Hypothesis: the estimate is unbiased; each channel within 4 standard errors (400 frames of 500
// paths, seed 1) plus 1e-3 relative for the quadrature.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "estimate.h"
#include "registered_strategies.h"
#include "scene_builder.h"
#include "tracer/bsdf.h"

namespace {

using namespace tracer;

constexpr float kRoughness = 0.5f;

/// Cube [-1, 1]^3 with inward faces, all emitting 1 from the inside, matte white.
Scene furnace() {
  Scene scene;
  Material wall = trs_test::matte(glm::vec3(1.0f), kRoughness);
  wall.emissive_factor = glm::vec3(1.0f);
  const std::uint32_t m = trs_test::add_material(scene, wall);
  const glm::vec3 c[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                          {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  // Counter-clockwise seen from inside.
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                           {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};
  for (const auto& f : faces) trs_test::add_quad(scene, c[f[0]], c[f[1]], c[f[2]], c[f[3]], m);
  return scene;
}

/// Directional albedo: the integral of f(wo, wi) |cos| over the hemisphere, midpoint rule in
/// (cos theta, phi), where the solid-angle measure is uniform.
double albedo(const Bsdf& bsdf, glm::vec3 n, glm::vec3 wo) {
  constexpr int kTheta = 800, kPhi = 400;
  const glm::vec3 t = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0)
                                                                         : glm::vec3(0, 1, 0)));
  const glm::vec3 b = glm::cross(n, t);
  double sum = 0.0;
  for (int i = 0; i < kTheta; ++i) {
    const double cos_theta = (i + 0.5) / kTheta;
    const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
    for (int j = 0; j < kPhi; ++j) {
      const double phi = 2.0 * std::numbers::pi * (j + 0.5) / kPhi;
      const glm::vec3 wi = float(sin_theta * std::cos(phi)) * t +
                           float(sin_theta * std::sin(phi)) * b + float(cos_theta) * n;
      sum += bsdf.eval(wo, wi).g;
    }
  }
  return sum * 2.0 * std::numbers::pi / (double(kTheta) * kPhi);
}

TEST(Furnace, OneBounceReturnsEmissionPlusAlbedo) {
  const Scene scene = furnace();
  const Geometry geometry(scene);
  Emitters emitters(scene, trs_test::kCpuSampler);
  const glm::vec3 eye(0.2f, -0.3f, 0.1f), target(0.4f, 0.1f, -1.0f);  // onto the z = -1 wall
  const Ray ray{eye, glm::normalize(target - eye)};
  const Bsdf bsdf({glm::vec3(1.0f), 0.0f, kRoughness}, {0, 0, 1});
  const double expected = 1.0 + albedo(bsdf, {0, 0, 1}, -ray.direction);
  for (const std::string& kind : trs_test::every_strategy()) {
    StrategyOptions options;
    options.kind = kind;
    options.lights = 5000;
    auto strategy = make_light_strategy(emitters, options);
    for (unsigned depth : {0u, 1u}) {
      const trs_test::Estimate e = trs_test::estimate_radiance(
          scene, geometry, emitters, *strategy, ray, depth, 400, 500, 1);
      const glm::dvec3 want(depth == 0 ? 1.0 : expected);
      EXPECT_TRUE(trs_test::agrees(e, want, 4.0, 1e-3))
          << kind << " depth " << depth << "\n" << trs_test::describe(e, want);
    }
  }
}

}  // namespace
