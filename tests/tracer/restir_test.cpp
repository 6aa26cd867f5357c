// `restir` through the renderer: reservoirs reused across the passes of a pixel and between
// neighbouring pixels (tracer/src/reuse.h).
//
// Scene: a floor lit by a one-sided textured panel standing on it, the floor behind the panel
// unlit by it, a second emitter above lighting the whole floor; seen from above, so that the
// pixels just in front of the panel have neighbours behind it, whose targets are zero where
// theirs are not: where reuse is biased unless its weights account for every domain.
//
// Unbiased. Hypothesis: with temporal and spatial reuse, either alone, and neither, weighed
// pairwise (the default) or by the balance heuristic, the expected image is that of `ris` (unbiased, tested against quadrature in analytic_test.cpp). Test: 40
// renders of 8 passes (seeds 1..40) per configuration and of `ris` (seeds 1001..1040); each
// image column's mean luminance, Welch's z between the two samples of 40 column means; every
// column |z| < 4.4 (two-sided p = 1e-5, family alpha 0.01 over 24 columns x 9 comparisons by
// Sidak: 6 configurations here, 3 frames of an animation below). Reuse with Bitterli et al.'s 1/M weights (weights=uniform), biased where domains
// differ, must fail the same check.
//
// Convergence. The passes of one image are correlated, yet its error must fall as passes grow.
// Hypothesis: relMSE (against the mean of the `ris` renders) falls at least as 1/passes^0.5.
// Test: temporal reuse on, 8 seeds at 2, 4, 8, 16 and 32 passes; least-squares slope of log
// relMSE against log passes below -0.5 (`ris`'s independent passes give -1.05, restir's -0.71:
// its passes share samples). Reuse with uniform weights, whose error stops at its bias, must
// not (-0.38).

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "luminance.h"
#include "scene_builder.h"
#include "tracer/renderer.h"

namespace {

using namespace tracer;

constexpr unsigned kWidth = 24, kHeight = 16, kPasses = 8, kSeeds = 40;

Scene panel_on_floor() {
  Scene scene = trs_test::floor_seen_from_above();
  trs_test::add_standing_panel(scene, 8, 0.3);
  Material sky;
  sky.emissive_factor = glm::vec3(0.3f);
  trs_test::add_quad(scene, {-1, 5, 1}, {-1, 5, -1}, {1, 5, -1}, {1, 5, 1}, trs_test::add_material(scene, sky));
  return scene;
}

/// Luminance per pixel of one render of each of animation frames 0 to `frames` - 1.
std::vector<std::vector<double>> render_frames(const Scene& scene, const StrategyOptions& strategy, unsigned passes,
                                               std::uint64_t seed, unsigned frames) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.spp = passes;
  settings.max_depth = 1;
  settings.seed = seed;
  settings.threads = 2;
  settings.strategy = strategy;
  settings.strategy.lights = 256;
  settings.sampler = trs_test::kCpuSampler;
  Renderer renderer(scene, settings);
  const std::atomic<bool> cancel{false};
  std::vector<std::vector<double>> images;
  for (unsigned f = 0; f < frames; ++f) {
    if (f > 0) renderer.set_frame(f);
    const RenderResult r = renderer.render({}, cancel);
    std::vector<double>& y = images.emplace_back(r.rgb.size() / 3);
    for (std::size_t i = 0; i < y.size(); ++i) y[i] = trs::luminance(r.rgb[3 * i], r.rgb[3 * i + 1], r.rgb[3 * i + 2]);
  }
  return images;
}

std::vector<double> render(const Scene& scene, const StrategyOptions& strategy, unsigned passes, std::uint64_t seed) {
  return render_frames(scene, strategy, passes, seed, 1)[0];
}

StrategyOptions restir(std::map<std::string, std::string> parameters) {
  StrategyOptions o;
  o.kind = "restir";
  o.parameters = std::move(parameters);
  o.parameters.emplace("radius", "4");
  return o;
}

/// Per seed, each column's mean luminance; and, where `pixels` is given, the mean image.
std::vector<std::vector<double>> column_means(const Scene& scene, const StrategyOptions& strategy, std::uint64_t first_seed,
                                              std::vector<double>* pixels = nullptr) {
  std::vector<std::vector<double>> means;
  if (pixels) pixels->assign(kWidth * kHeight, 0.0);
  for (std::uint64_t s = 0; s < kSeeds; ++s) {
    const std::vector<double> y = render(scene, strategy, kPasses, first_seed + s);
    std::vector<double> columns(kWidth, 0.0);
    for (unsigned i = 0; i < y.size(); ++i) {
      columns[i % kWidth] += y[i] / kHeight;
      if (pixels) (*pixels)[i] += y[i] / kSeeds;
    }
    means.push_back(columns);
  }
  return means;
}

/// Per frame, per seed, each column's mean luminance, frames 0 to `frames` - 1.
std::vector<std::vector<std::vector<double>>> frame_column_means(const Scene& scene, const StrategyOptions& strategy,
                                                                 std::uint64_t first_seed, unsigned frames) {
  std::vector<std::vector<std::vector<double>>> means(frames);
  for (std::uint64_t s = 0; s < kSeeds; ++s) {
    const std::vector<std::vector<double>> images = render_frames(scene, strategy, kPasses, first_seed + s, frames);
    for (unsigned f = 0; f < frames; ++f) {
      std::vector<double> columns(kWidth, 0.0);
      for (unsigned i = 0; i < images[f].size(); ++i) columns[i % kWidth] += images[f][i] / kHeight;
      means[f].push_back(columns);
    }
  }
  return means;
}

/// Welch's z of each column between two samples of column means.
std::vector<double> welch_z(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
  std::vector<double> z(kWidth);
  for (unsigned c = 0; c < kWidth; ++c) {
    double ma = 0, mb = 0, va = 0, vb = 0;
    for (const auto& s : a) ma += s[c] / a.size();
    for (const auto& s : b) mb += s[c] / b.size();
    for (const auto& s : a) va += (s[c] - ma) * (s[c] - ma) / (a.size() - 1);
    for (const auto& s : b) vb += (s[c] - mb) * (s[c] - mb) / (b.size() - 1);
    const double se = std::sqrt(va / a.size() + vb / b.size());
    z[c] = se > 0 ? (ma - mb) / se : (ma == mb ? 0.0 : INFINITY);
  }
  return z;
}

double max_abs(const std::vector<double>& z) {
  double m = 0;
  for (double v : z) m = std::max(m, std::abs(v));
  return m;
}

constexpr double kZ = 4.4;

class Restir : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(panel_on_floor());
    StrategyOptions ris;
    ris.kind = "ris";
    pixels_ = new std::vector<double>;
    reference_ = new std::vector<std::vector<double>>(column_means(*scene_, ris, 1001, pixels_));
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete reference_;
    delete pixels_;
  }
  static Scene* scene_;
  static std::vector<std::vector<double>>* reference_;  ///< ris's column means per seed
  static std::vector<double>* pixels_;                  ///< ris's mean image
};
Scene* Restir::scene_ = nullptr;
std::vector<std::vector<double>>* Restir::reference_ = nullptr;
std::vector<double>* Restir::pixels_ = nullptr;

TEST_F(Restir, EveryReuseIsUnbiased) {
  for (const auto& parameters : std::vector<std::map<std::string, std::string>>{
           {{"temporal", "on"}}, {}, {{"temporal", "on"}, {"neighbours", "0"}}, {{"neighbours", "0"}},
           {{"temporal", "on"}, {"weights", "balance"}}}) {
    std::string name;
    for (const auto& [k, v] : parameters) name += k + "=" + v + " ";
    const std::vector<double> z = welch_z(column_means(*scene_, restir(parameters), 1), *reference_);
    EXPECT_LT(max_abs(z), kZ) << "restir " << name;
    std::printf("restir %s: max z %.2f\n", name.c_str(), max_abs(z));
  }
}

TEST_F(Restir, UniformWeightsAreCaughtBiased) {
  const std::vector<double> z =
      welch_z(column_means(*scene_, restir({{"weights", "uniform"}, {"temporal", "on"}}), 1), *reference_);
  EXPECT_GT(max_abs(z), kZ);
  std::printf("uniform: max z %.2f\n", max_abs(z));
}

// An animated emission: the panel dims and brightens over three frames. Every frame starts
// without history (the emission its reservoirs were drawn from is gone), so each is unbiased
// as a still is. Same test as above, per frame (3 frames x 24 columns more in the family).
TEST_F(Restir, AnAnimatedEmissionStaysUnbiasedFrameByFrame) {
  Scene scene = panel_on_floor();
  scene.materials[1].emissive_factor_keys =
      Keyframes{{0.0f, 1.0f / 24.0f, 2.0f / 24.0f}, {glm::vec3(2.0f), glm::vec3(0.3f), glm::vec3(4.0f)}, false};
  StrategyOptions ris;
  ris.kind = "ris";
  const auto expected = frame_column_means(scene, ris, 1001, 3);
  const auto reused = frame_column_means(scene, restir({{"temporal", "on"}}), 1, 3);
  for (unsigned f = 0; f < 3; ++f) {
    const std::vector<double> z = welch_z(reused[f], expected[f]);
    EXPECT_LT(max_abs(z), kZ) << "frame " << f;
    std::printf("frame %u: max z %.2f\n", f, max_abs(z));
  }
}

/// The least-squares slope of log relMSE against log passes, for `strategy`; `reference` per
/// pixel.
double convergence_slope(const Scene& scene, const StrategyOptions& strategy, const std::vector<double>& reference) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (unsigned passes = 2; passes <= 32; passes *= 2) {
    double rel = 0;
    for (std::uint64_t s = 0; s < 8; ++s) {
      const std::vector<double> y = render(scene, strategy, passes, 1 + s);
      for (std::size_t i = 0; i < y.size(); ++i)
        rel += (y[i] - reference[i]) * (y[i] - reference[i]) / (reference[i] * reference[i] + 1e-3) / (8.0 * y.size());
    }
    const double x = std::log(double(passes)), l = std::log(rel);
    sx += x, sy += l, sxx += x * x, sxy += x * l, ++n;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST_F(Restir, ErrorFallsAsPassesGrow) {
  const double slope = convergence_slope(*scene_, restir({{"temporal", "on"}}), *pixels_);
  EXPECT_LT(slope, -0.5);
  RecordProperty("slope", std::to_string(slope));
  std::printf("relMSE slope against passes: %.3f\n", slope);
  // Biased, its error stops falling at its bias.
  EXPECT_GT(convergence_slope(*scene_, restir({{"weights", "uniform"}, {"temporal", "on"}}), *pixels_), -0.5);
}

}  // namespace
