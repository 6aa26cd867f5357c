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

#include "quad_over_plane.h"

namespace {

using namespace tracer;
using namespace trs_test;

/// Whether every strategy's estimate along the bench's ray agrees with the quadrature.
void expect_every_strategy_agrees(const QuadOverPlane& bench, const glm::dvec3& expected,
                                  const std::vector<std::string>& kinds) {
  for (const std::string& kind : kinds) {
    const StrategyOptions o = options(kind);
    auto s = make_light_strategy(*bench.emitters, o);
    const Estimate e = bench.run(*s, 1);
    EXPECT_TRUE(trs_test::agrees(e, expected, kSigmas, kQuadratureSlack))
        << kind << "\n" << trs_test::describe(e, expected);
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
  expect_every_strategy_agrees(*bench_, expected_, trs_test::every_strategy());
}

// `ris` over every strategy it can draw its candidates from.
TEST_F(AnalyticQuad, RisConvergesWhereverItsCandidatesComeFrom) {
  for (const std::string& source : trs_test::every_strategy()) {
    if (!resamplable(source)) continue;
    StrategyOptions o = options("ris");
    o.candidates_from = source;
    auto s = make_light_strategy(*bench_->emitters, o);
    const Estimate e = bench_->run(*s, 3);
    EXPECT_TRUE(trs_test::agrees(e, expected_, kSigmas, kQuadratureSlack))
        << "ris over " << source << "\n" << trs_test::describe(e, expected_);
  }
}

// The tree with each importance and each source of the lights' power: the emitter's two
// triangles cover different halves of its texture, so that the whole map's mean misjudges them.
TEST_F(AnalyticQuad, TreeConvergesWithEitherImportanceAndPower) {
  for (const std::string& kind : {"tree", "tree-texel"}) {
    for (TreeImportance importance : {TreeImportance::pbrt, TreeImportance::cycles}) {
      for (TreePower power : {TreePower::exact, TreePower::image_mean}) {
        StrategyOptions o = options(kind);
        o.tree = {importance, power};
        auto s = make_light_strategy(*bench_->emitters, o);
        const Estimate e = bench_->run(*s, 5);
        EXPECT_TRUE(trs_test::agrees(e, expected_, kSigmas, kQuadratureSlack))
            << kind << ", " << to_string(importance) << ", " << to_string(power) << "\n"
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
  expect_every_strategy_agrees(*bench, bench->expected(), {"trs", "ris"});
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
                               {"power", "trs", "ris"});
}

// One light per frame, in expectation: frames with none are common (each triangle's count is
// rounded stochastically), and only the N / N_target factor keeps the estimator unbiased.
TEST_F(AnalyticQuad, TrsWithOneLightPerFrameIsUnbiased) {
  auto s = strategy(*bench_->emitters, "trs", 1);
  const Estimate e = bench_->run(*s);
  EXPECT_TRUE(trs_test::agrees(e, expected_, kSigmas, kQuadratureSlack))
      << trs_test::describe(e, expected_);
}

TEST_F(AnalyticQuad, StrategiesAgreeWithOneAnother) {
  auto uniform = strategy(*bench_->emitters, "uniform");
  auto trs = strategy(*bench_->emitters, "trs");
  const Estimate a = bench_->run(*uniform, 11), b = bench_->run(*trs, 12);
  for (int c = 0; c < 3; ++c) {
    const double combined = std::hypot(a.standard_error[c], b.standard_error[c]);
    EXPECT_LT(std::abs(a.mean[c] - b.mean[c]), kSigmas * combined) << "channel " << c;
  }
}

// Deliberately wrong: point lights weighed by p(x) alone, without the set's N / N_target.
class TrsWithoutSetSize : public LightStrategy {
 public:
  explicit TrsWithoutSetSize(Emitters& emitters)
      : trs_(strategy(emitters, "trs", 1)) {}
  std::string name() const override { return "wrong"; }
  void begin_pass(std::uint64_t seed) override { trs_->begin_pass(seed); }
  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
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
  // Points drawn in proportion to power, weighed as if drawn uniformly.
  DrawnByOneWeighedByAnother mismatched(strategy(*bench_->emitters, "power"),
                                        strategy(*bench_->emitters, "uniform"));
  TrsWithoutSetSize unscaled(*bench_->emitters);
  // Used as they are, and resampled: resampling does not hide a wrong source density.
  for (unsigned candidates : {1u, kDefaultCandidates}) {
    WithCandidates mismatched_resampled(mismatched, candidates), unscaled_resampled(unscaled, candidates);
    EXPECT_FALSE(trs_test::agrees(bench_->run(mismatched_resampled, 1), expected_, kSigmas, kQuadratureSlack))
        << candidates;
    EXPECT_FALSE(trs_test::agrees(bench_->run(unscaled_resampled, 1), expected_, kSigmas, kQuadratureSlack))
        << candidates;
  }
}

}  // namespace
