// An emissive quad with a known texture above a plane: the radiance the plane reflects along one
// ray, direct lighting only, computed by quadrature over the texels, against the mean of each
// light strategy.
//
// Hypothesis: every strategy's estimator is unbiased. Test: each channel's mean lies within 4
// standard errors of the quadrature value (plus 1e-4 relative for the quadrature), the standard
// error from 400 independent frames of 500 paths each; 4 sigma two-sided is p = 6e-5 per
// comparison, about 1e-3 over the comparisons of this file. Seeds fixed. Two deliberately wrong
// strategies must fail the same check.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <vector>
#include <string_view>

#include "estimate.h"
#include "scene_builder.h"
#include "tracer/bsdf.h"

namespace {

using namespace tracer;
using trs_test::Estimate;

constexpr double kSigmas = 4.0;
constexpr double kQuadratureSlack = 1e-4;
constexpr unsigned kFrames = 400, kPaths = 500;
constexpr float kStrength = 3.0f;
constexpr std::uint32_t kTexWidth = 8, kTexHeight = 4;

/// The emitter covers [-0.5, 0.5]^2 at z = 1, facing down; the plane z = 0 faces up.
struct QuadOverPlane {
  Scene scene;
  glm::vec3 point{0.1f, 0.15f, 0.0f};                 ///< where the ray meets the plane
  glm::vec3 eye{0.45f, -0.1f, 0.3f};                  ///< where the ray starts
  std::unique_ptr<Geometry> geometry;
  std::unique_ptr<Emitters> emitters;

  explicit QuadOverPlane(const lightsampler::SamplerOptions& sampler = trs_test::kCpuSampler) {
    Material light;
    light.base_color = glm::vec3(0.0f);
    light.emissive_factor = glm::vec3(1.0f, 0.9f, 0.8f);
    light.emissive_strength = kStrength;
    light.emissive_texture = trs_test::add_random_texture(scene, kTexWidth, kTexHeight, 0.4, 3);
    const std::uint32_t emitter = trs_test::add_material(scene, light);
    const std::uint32_t floor = trs_test::add_material(scene, trs_test::matte({0.8f, 0.6f, 0.4f}, 0.7f));
    // Corners in UV order (0,0) (1,0) (1,1) (0,1); clockwise seen from above: facing down.
    trs_test::add_quad(scene, {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, 0.5f, 1},
                       {0.5f, -0.5f, 1}, emitter);
    trs_test::add_quad(scene, {-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}, floor);
    geometry = std::make_unique<Geometry>(scene.mesh);
    emitters = std::make_unique<Emitters>(scene, sampler);
  }

  Ray ray() const { return {eye, glm::normalize(point - eye)}; }

  /// Emitted radiance of texel (i, j): texture times factor times strength.
  glm::dvec3 radiance_at(std::uint32_t i, std::uint32_t j) const {
    const Material& m = scene.materials[0];
    const glm::vec3 t = scene.textures[0].texels[j * kTexWidth + i];
    return glm::dvec3(t * m.emissive_factor * m.emissive_strength);
  }

  /// The integral over the quad of f(wo, wi) Le cos(light) / r^2, midpoint rule on 16 x 16
  /// sub-cells of every texel (the integrand is smooth inside a texel).
  glm::dvec3 expected() const {
    const Material& m = scene.materials[1];
    const Bsdf bsdf({m.base_color, m.metallic, m.roughness}, {0, 0, 1});
    const glm::vec3 wo = glm::normalize(eye - point);
    constexpr int kSub = 16;
    glm::dvec3 sum(0.0);
    // add_quad gives corner k UV (0,0) (1,0) (1,1) (0,1); here those corners are
    // (-.5,-.5) (-.5,.5) (.5,.5) (.5,-.5): u runs along +y, v along +x.
    for (std::uint32_t j = 0; j < kTexHeight; ++j) {
      for (std::uint32_t i = 0; i < kTexWidth; ++i) {
        const glm::dvec3 le = radiance_at(i, j);
        if (le == glm::dvec3(0.0)) continue;
        for (int a = 0; a < kSub; ++a) {
          for (int b = 0; b < kSub; ++b) {
            const double u = (i + (a + 0.5) / kSub) / kTexWidth;
            const double v = (j + (b + 0.5) / kSub) / kTexHeight;
            const glm::vec3 y(float(-0.5 + v), float(-0.5 + u), 1.0f);
            const glm::vec3 d = y - point;
            const float r2 = glm::dot(d, d);
            const glm::vec3 wi = d / std::sqrt(r2);
            const double cos_light = wi.z;  // the emitter faces -z
            const double area = 1.0 / (double(kTexWidth) * kTexHeight * kSub * kSub);
            sum += glm::dvec3(bsdf.eval(wo, wi)) * le * (cos_light / r2 * area);
          }
        }
      }
    }
    return sum;
  }

  Estimate run(LightStrategy& strategy, std::uint64_t seed = 1, unsigned candidates = 1) const {
    return trs_test::estimate_radiance(scene, *geometry, *emitters, strategy, ray(), 1, kFrames,
                                       kPaths, seed, candidates);
  }
};

StrategyOptions options(StrategyKind kind, double lights = 2000) {
  StrategyOptions o;
  o.kind = kind;
  o.lights = lights;
  o.seed = 7;
  return o;
}

std::unique_ptr<LightStrategy> strategy(const Emitters& emitters, StrategyKind kind,
                                        double lights = 2000) {
  return make_light_strategy(emitters, options(kind, lights));
}

const std::vector<StrategyKind> kEveryStrategy = {StrategyKind::uniform, StrategyKind::power,
                                                  StrategyKind::trs,     StrategyKind::ris,
                                                  StrategyKind::tree,    StrategyKind::texel,
                                                  StrategyKind::tree_texel};

/// Whether every strategy's estimate along the bench's ray agrees with the quadrature.
void expect_every_strategy_agrees(const QuadOverPlane& bench, const glm::dvec3& expected,
                                  const std::vector<StrategyKind>& kinds) {
  for (StrategyKind kind : kinds) {
    const StrategyOptions o = options(kind);
    auto s = make_light_strategy(*bench.emitters, o);
    const Estimate e = bench.run(*s, 1, connection_candidates(o));
    EXPECT_TRUE(trs_test::agrees(e, expected, kSigmas, kQuadratureSlack))
        << to_string(kind) << "\n" << trs_test::describe(e, expected);
  }
}

class AnalyticQuad : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    bench_ = new QuadOverPlane;
    expected_ = bench_->expected();
  }
  static void TearDownTestSuite() { delete bench_; }
  static QuadOverPlane* bench_;
  static glm::dvec3 expected_;
};
QuadOverPlane* AnalyticQuad::bench_ = nullptr;
glm::dvec3 AnalyticQuad::expected_;

TEST_F(AnalyticQuad, EveryStrategyConvergesToTheQuadrature) {
  ASSERT_GT(expected_.g, 0.0);
  expect_every_strategy_agrees(*bench_, expected_, kEveryStrategy);
}

// `ris` over every strategy it can draw its candidates from.
TEST_F(AnalyticQuad, RisConvergesWhereverItsCandidatesComeFrom) {
  for (StrategyKind source : kEveryStrategy) {
    if (!resamplable(source)) continue;
    StrategyOptions o = options(StrategyKind::ris);
    o.candidates_from = source;
    auto s = make_light_strategy(*bench_->emitters, o);
    const Estimate e = bench_->run(*s, 3, connection_candidates(o));
    EXPECT_TRUE(trs_test::agrees(e, expected_, kSigmas, kQuadratureSlack))
        << "ris over " << to_string(source) << "\n" << trs_test::describe(e, expected_);
  }
}

// The tree with each importance and each source of the lights' power: the emitter's two
// triangles cover different halves of its texture, so that the whole map's mean misjudges them.
TEST_F(AnalyticQuad, TreeConvergesWithEitherImportanceAndPower) {
  for (StrategyKind kind : {StrategyKind::tree, StrategyKind::tree_texel}) {
    for (TreeImportance importance : {TreeImportance::pbrt, TreeImportance::cycles}) {
      for (TreePower power : {TreePower::exact, TreePower::image_mean}) {
        StrategyOptions o = options(kind);
        o.tree = {importance, power};
        auto s = make_light_strategy(*bench_->emitters, o);
        const Estimate e = bench_->run(*s, 5);
        EXPECT_TRUE(trs_test::agrees(e, expected_, kSigmas, kQuadratureSlack))
            << to_string(kind) << ", " << to_string(importance) << ", " << to_string(power) << "\n"
            << trs_test::describe(e, expected_);
      }
    }
  }
}

// The lights of the Vulkan sampler, read back and resampled on the host like the CPU sampler's.
// Skipped without a Vulkan device, unless LIGHTSAMPLER_REQUIRE_VULKAN=1.
TEST(VulkanLights, TrsAndRisConvergeToTheQuadrature) {
  std::unique_ptr<QuadOverPlane> bench;
  try {
    bench = std::make_unique<QuadOverPlane>(
        lightsampler::SamplerOptions{.backend = lightsampler::Backend::vulkan});
  } catch (const lightsampler::VulkanUnavailable& e) {
    const char* required = std::getenv("LIGHTSAMPLER_REQUIRE_VULKAN");
    if (required && std::string_view(required) == "1") FAIL() << "Vulkan is unavailable: " << e.what();
    GTEST_SKIP() << "Vulkan unavailable: " << e.what();
  }
  expect_every_strategy_agrees(*bench, bench->expected(), {StrategyKind::trs, StrategyKind::ris});
}

// The lights drawn from parts of the emitter's triangles (lightsampler/refinement.h), brought
// back to the triangles: the same estimate; `power` reads the per-triangle integrals through it,
// `ris` resamples the lights.
TEST(RefinedLightSampler, PowerTrsAndRisConvergeToTheQuadrature) {
  lightsampler::SamplerOptions sampler = trs_test::kCpuSampler;
  sampler.refinement = {.min_acceptance = 0.9f, .min_texels = 1.0f, .min_split_gain = 1.0f};  // split even where it barely pays
  const QuadOverPlane bench(sampler);
  lightsampler::Frame frame;
  bench.emitters->sampler().generate({.seed = 1, .target_count = 1000}, frame);
  ASSERT_TRUE(std::any_of(frame.passes.begin(), frame.passes.end(),
                          [](const lightsampler::PassTime& p) { return p.pass == lightsampler::Pass::refinement; }))
      << "the emitter was not split";
  expect_every_strategy_agrees(bench, bench.expected(),
                               {StrategyKind::power, StrategyKind::trs, StrategyKind::ris});
}

// One light per frame, in expectation: frames with none are common (each triangle's count is
// rounded stochastically), and only the N / N_target factor keeps the estimator unbiased.
TEST_F(AnalyticQuad, TrsWithOneLightPerFrameIsUnbiased) {
  auto s = strategy(*bench_->emitters, StrategyKind::trs, 1);
  const Estimate e = bench_->run(*s);
  EXPECT_TRUE(trs_test::agrees(e, expected_, kSigmas, kQuadratureSlack))
      << trs_test::describe(e, expected_);
}

TEST_F(AnalyticQuad, StrategiesAgreeWithOneAnother) {
  auto uniform = strategy(*bench_->emitters, StrategyKind::uniform);
  auto trs = strategy(*bench_->emitters, StrategyKind::trs);
  const Estimate a = bench_->run(*uniform, 11), b = bench_->run(*trs, 12);
  for (int c = 0; c < 3; ++c) {
    const double combined = std::hypot(a.standard_error[c], b.standard_error[c]);
    EXPECT_LT(std::abs(a.mean[c] - b.mean[c]), kSigmas * combined) << "channel " << c;
  }
}

// Deliberately wrong: points drawn in proportion to power, weighed as if drawn uniformly.
class PowerDrawnUniformWeighed : public LightStrategy {
 public:
  explicit PowerDrawnUniformWeighed(const Emitters& emitters)
      : power_(strategy(emitters, StrategyKind::power)),
        uniform_(strategy(emitters, StrategyKind::uniform)) {}
  std::string name() const override { return "wrong"; }
  std::optional<LightSample> sample(const LightRandom& random,
                                    const ShadingPoint& at) const override {
    auto s = power_->sample(random, at);
    if (s) s->pdf = s->mis_pdf = pdf(s->light, s->b1, s->b2, at);
    return s;
  }
  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return uniform_->pdf(light, b1, b2, from);
  }

 private:
  std::unique_ptr<LightStrategy> power_, uniform_;
};

// Deliberately wrong: point lights weighed by p(x) alone, without the set's N / N_target.
class TrsWithoutSetSize : public LightStrategy {
 public:
  explicit TrsWithoutSetSize(const Emitters& emitters)
      : trs_(strategy(emitters, StrategyKind::trs, 1)) {}
  std::string name() const override { return "wrong"; }
  void begin_frame(std::uint64_t frame) override { trs_->begin_frame(frame); }
  std::optional<LightSample> sample(const LightRandom& random,
                                    const ShadingPoint& at) const override {
    auto s = trs_->sample(random, at);
    if (s) s->pdf = s->mis_pdf;
    return s;
  }
  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return trs_->pdf(light, b1, b2, from);
  }

 private:
  std::unique_ptr<LightStrategy> trs_;
};

TEST_F(AnalyticQuad, TheCheckRejectsWrongStrategies) {
  PowerDrawnUniformWeighed mismatched(*bench_->emitters);
  TrsWithoutSetSize unscaled(*bench_->emitters);
  // Used as they are, and resampled: resampling does not hide a wrong source density.
  for (unsigned candidates : {1u, kDefaultCandidates}) {
    EXPECT_FALSE(trs_test::agrees(bench_->run(mismatched, 1, candidates), expected_, kSigmas,
                                  kQuadratureSlack)) << candidates;
    EXPECT_FALSE(trs_test::agrees(bench_->run(unscaled, 1, candidates), expected_, kSigmas,
                                  kQuadratureSlack)) << candidates;
  }
}

}  // namespace
