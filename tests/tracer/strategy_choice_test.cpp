// `auto`'s choice by a pilot (tracer/src/strategy_choice.cpp): each of power, trs and ris renders
// a few passes over a grid of the image's pixels, until the most efficient (least relative
// variance times counted work per pass) is known well enough; the cheapest within kCheaperMargin
// of it renders the image.
//
// The pilot is deterministic (its seed is its own, its work counted rather than timed), so these
// tests are exact checks of its outcome on three floors, each lit so that one thing decides:
//   - the texture: a panel whose texels are 90% black. Drawing uniformly on it (power) wastes 9 of
//     10 samples, so power's efficiency must be below half the best, and power not chosen;
//   - orientation: two equal emitters above the floor, one facing it, one facing away. Drawing by
//     power or by the texels picks the one facing away half the time, while ris' four candidates
//     nearly always hold the other: ris must be chosen, at least 1.5 times as efficient as power;
//   - cost: one small emitter far above the floor, flat, whose samples all bring about the same,
//     and 100,000 point lights asked a pass (a render of 768 pixels): the point lights that trs
//     and ris draw each pass cost more than the paths, so power must be chosen, trs below half
//     its efficiency.
// A pilot that weighed noise alone would choose ris on the third floor; one that weighed cost
// alone, power on the first two. Where one strategy is far ahead (the second floor) the pilot
// stops at its first check.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "scene_builder.h"
#include "tracer/renderer.h"
#include "tracer/strategy_registry.h"

namespace {

using namespace tracer;

constexpr unsigned kWidth = 32, kHeight = 24;

/// An emissive quad of half-size `h` at height `y`, facing down (towards the floor) or up.
void add_ceiling_light(Scene& scene, float h, float y, bool facing_down, glm::vec3 emission) {
  Material m;
  m.emissive_factor = emission;
  const std::uint32_t material = trs_test::add_material(scene, m);
  if (facing_down)
    trs_test::add_quad(scene, {-h, y, h}, {-h, y, -h}, {h, y, -h}, {h, y, h}, material);
  else
    trs_test::add_quad(scene, {-h, y, h}, {h, y, h}, {h, y, -h}, {-h, y, -h}, material);
}

Scene sparse_panel() {
  Scene scene = trs_test::floor_seen_from_above();
  trs_test::add_standing_panel(scene, 16, 0.9);
  return scene;
}

Scene facing_away() {
  Scene scene = trs_test::floor_seen_from_above();
  add_ceiling_light(scene, 1.0f, 5.0f, true, glm::vec3(1.0f));
  add_ceiling_light(scene, 1.0f, 5.2f, false, glm::vec3(1.0f));
  return scene;
}

Scene small_far_light() {
  Scene scene = trs_test::floor_seen_from_above();
  add_ceiling_light(scene, 0.05f, 8.0f, true, glm::vec3(100.0f));
  return scene;
}

RenderSettings settings(std::uint64_t seed = 1, unsigned threads = 2) {
  RenderSettings s;
  s.width = kWidth;
  s.height = kHeight;
  s.spp = 2;
  s.max_depth = 1;
  s.seed = seed;
  s.threads = threads;
  s.strategy.kind = kAutoStrategy;
  s.strategy.lights = auto_lights(kWidth, kHeight, s.max_depth);
  s.sampler = trs_test::kCpuSampler;
  return s;
}

RenderResult render(const Scene& scene, const RenderSettings& s) {
  const std::atomic<bool> cancel{false};
  return Renderer(scene, s).render({}, cancel);
}

const PilotMeasure& measure_of(const StrategyChoice& choice, const std::string& strategy) {
  for (const PilotMeasure& m : choice.pilot)
    if (m.strategy == strategy) return m;
  throw std::runtime_error("no pilot measure of " + strategy);
}

/// Each strategy's efficiency over the chosen one's, for failure messages.
std::string efficiencies(const StrategyChoice& choice) {
  std::string text = "chose " + choice.options.kind + ":";
  const double best = measure_of(choice, choice.options.kind).efficiency;
  for (const PilotMeasure& m : choice.pilot) text += " " + m.strategy + " " + std::to_string(m.efficiency / best);
  return text;
}

// Which strategy the pilot's measures make render: the most efficient, unless a cheaper one is
// within kCheaperMargin of it. Costs as power's, trs' and ris' usually compare.
TEST(StrategyChoice, TheCheapestCloseToTheMostEfficientRenders) {
  const auto pilot = [](double power, double trs, double ris) {
    std::vector<PilotMeasure> p = {{"power"}, {"trs"}, {"ris"}};
    const double efficiency[] = {power, trs, ris}, cost[] = {1.0, 1.1, 1.4};
    for (std::size_t i = 0; i < p.size(); ++i) {
      p[i].efficiency = efficiency[i];
      p[i].cost = cost[i];
    }
    return p;
  };
  EXPECT_EQ(strategy_to_render(pilot(0.5, 0.7, 1.0)), 2u);  // none within the margin
  EXPECT_EQ(strategy_to_render(pilot(0.92, 0.5, 1.0)), 0u);  // power within it
  EXPECT_EQ(strategy_to_render(pilot(0.85, 0.92, 1.0)), 1u);  // trs within it, power not
  EXPECT_EQ(strategy_to_render(pilot(0.92, 0.95, 1.0)), 0u);  // both: the cheaper
  EXPECT_EQ(strategy_to_render(pilot(1.0, 1.2, 0.1)), 1u);  // the most efficient, cheapest within
  EXPECT_EQ(strategy_to_render(pilot(1.0, 1.0, 1.0)), 0u);  // a tie: the cheapest
}

// When the pilot may stop, on noises made up pixel by pixel: a strategy far behind is known to
// be at once; one close to the most efficient only where the ratio of their noises is known to
// better than the indifference (10%), as it is where their pixels' noises move together.
TEST(StrategyChoice, ThePilotStopsOnceNoOtherCanBeFarAhead) {
  const auto pilot = [](double efficiency) {
    std::vector<PilotMeasure> p = {{"power"}, {"trs"}};
    p[0].efficiency = 1.0;
    p[1].efficiency = efficiency;
    return p;
  };
  // 40 pixels whose noises spread 1 to 5 times: the log of the ratio of two means of such noises,
  // independent, is known to about 9%; of two that move together, exactly.
  std::vector<double> a(40), independent(40), together(40);
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = 1.0 + 4.0 * double(i % 20) / 19.0;
    independent[i] = 1.0 + 4.0 * double((i * 7 + 3) % 20) / 19.0;  // the same spread, other pixels
    together[i] = 1.05 * a[i];
  }
  EXPECT_TRUE(pilot_decided(pilot(0.3), {a, independent}));    // far behind, whatever the spread
  EXPECT_FALSE(pilot_decided(pilot(0.95), {a, independent}));  // close, and the ratio not known well
  EXPECT_TRUE(pilot_decided(pilot(0.95), {a, together}));      // close, and the ratio known
  EXPECT_TRUE(pilot_decided(pilot(3.0), {a, independent}));    // the second far ahead: it leads
  // One pixel holding most of both noises (a firefly in each, the second's a third brighter):
  // their ratio is that of two fireflies, however alike the other pixels. Leaving that pixel
  // out moves its log by a quarter, so a strategy at 0.8 may be ahead; taken as the pixels'
  // shares of both sums (the delta method), the ratio would seem known to 3%, and 0.8 behind.
  std::vector<double> firefly = together, brighter = together;
  firefly[7] = 1000.0;
  brighter[7] = 1333.0;
  EXPECT_FALSE(pilot_decided(pilot(0.8), {brighter, firefly}));
  EXPECT_TRUE(pilot_decided(pilot(0.3), {brighter, firefly}));  // that far behind, known

  // restir, close behind ris or close ahead: its measure already carries its blocks' error
  // (taken two standard errors up), which the stop does not count again, however large (its
  // relative_error here); it is known against the others as ris is, and ris against power decides.
  for (double restir : {0.97, 1.03}) {
    std::vector<PilotMeasure> p = {{"power"}, {"trs"}, {"ris"}, {"restir"}};
    const double efficiency[] = {0.3, 0.3, 1.0, restir};
    for (std::size_t i = 0; i < p.size(); ++i) p[i].efficiency = efficiency[i];
    p[3].relative_error = 0.5;
    EXPECT_TRUE(pilot_decided(p, {a, a, together})) << restir;
    p[0].efficiency = 0.97;  // power close to them, and not known well against ris
    EXPECT_FALSE(pilot_decided(p, {independent, a, a})) << restir;
  }
}

// What another round of the pilot is expected to win back (the knowledge gradient): after the
// round the other strategy's log efficiency ratio to the leader has error s' = s sqrt(p / (p + 2))
// (p passes so far), and its estimate has moved by N(0, s^2 - s'^2); the round pays where the
// other's expected efficiency then, e^(m' + s'^2 / 2), is above the leader's. Checked against
// that integral taken by quadrature, with noises whose ratio's standard error s is known by hand:
// noises of 26 pixels alternating 1 and 3 against 2 everywhere (sums 52 and 50): leaving a pixel
// out moves the log of the ratio to log(51/50) or log(49/50), +-log(51/49)/2 about their mean,
// and the jackknife's standard error sqrt(25/26 * 26 (log(51/49)/2)^2) = 2.5 log(51/49) ~ 0.1.
// It can never exceed what rendering with the leader is expected to lose, E[(e^d - 1)^+] with d
// ~ N(m, s^2), and it falls as the passes grow.
TEST(StrategyChoice, WhatAnotherRoundIsExpectedToWinBack) {
  std::vector<double> alternating(26), flat(26, 2.0);
  for (std::size_t i = 0; i < alternating.size(); ++i) alternating[i] = i % 2 ? 3.0 : 1.0;
  const double kSigma = 2.5 * std::log(51.0 / 49.0);
  const auto excess = [](double m, double sigma) {  // E[(e^d - 1)^+], d ~ N(m, sigma^2)
    double sum = 0.0;
    const double step = sigma / 1000.0;
    for (double d = step / 2.0; d < m + 12.0 * sigma; d += step)
      sum += std::expm1(d) * std::exp(-0.5 * (d - m) * (d - m) / (sigma * sigma));
    return sum * step / (sigma * std::sqrt(2.0 * std::numbers::pi));
  };
  const auto by_quadrature = [&](double m, unsigned passes) {
    const double after = kSigma * kSigma * passes / (passes + kPilotRoundPasses);
    return excess(m + 0.5 * after, std::sqrt(kSigma * kSigma - after));
  };
  const auto pilot = [](std::vector<double> efficiencies) {
    std::vector<PilotMeasure> p;
    for (std::size_t i = 0; i < efficiencies.size(); ++i) {
      p.push_back({kPilotStrategies[i]});
      p.back().efficiency = efficiencies[i];
    }
    return p;
  };
  for (double ratio : {1.0, 0.95, 0.8}) {  // the other strategy's efficiency over the leader's
    double before = std::numeric_limits<double>::infinity();
    for (unsigned passes : {kMinPilotPasses, 6u}) {
      const double gain = pilot_round_gain(pilot({1.0, ratio}), {flat, alternating}, passes);
      const double expected = by_quadrature(std::log(ratio), passes);
      EXPECT_NEAR(gain, expected, 1e-3 * expected) << ratio << ", " << passes;
      EXPECT_LT(gain, excess(std::log(ratio), kSigma)) << ratio << ", " << passes;
      EXPECT_LT(gain, before) << ratio << ", " << passes;
      before = gain;
    }
  }
  // Two others: their gains add. Their ratios known exactly: nothing to win back.
  EXPECT_NEAR(pilot_round_gain(pilot({1.0, 0.95, 0.8}), {flat, alternating, alternating}, kMinPilotPasses),
              by_quadrature(std::log(0.95), kMinPilotPasses) + by_quadrature(std::log(0.8), kMinPilotPasses), 1e-4);
  EXPECT_EQ(pilot_round_gain(pilot({1.0, 0.95}), {flat, flat}, kMinPilotPasses), 0.0);
}

/// The choice follows the rule above from the pilot's own measures, in rounds within the bounds.
void expect_consistent(const StrategyChoice& choice) {
  ASSERT_EQ(choice.pilot.size(), std::size(kPilotStrategies) + (choice.pilot_block_pixels > 0 ? 1 : 0));
  EXPECT_EQ(choice.options.kind, choice.pilot[strategy_to_render(choice.pilot)].strategy) << efficiencies(choice);
  EXPECT_GE(choice.pilot_passes, kMinPilotPasses);
  EXPECT_LE(choice.pilot_passes, kMaxPilotPasses);
  EXPECT_EQ(choice.pilot_passes % kPilotRoundPasses, 0u);
}

TEST(StrategyChoice, TheTextureDecides) {
  const StrategyChoice choice = render(sparse_panel(), settings()).strategy_choice;
  expect_consistent(choice);
  EXPECT_NE(choice.options.kind, "power") << efficiencies(choice);
  EXPECT_LT(measure_of(choice, "power").efficiency, 0.5 * measure_of(choice, choice.options.kind).efficiency)
      << efficiencies(choice);
}

TEST(StrategyChoice, OrientationDecides) {
  const StrategyChoice choice = render(facing_away(), settings()).strategy_choice;
  expect_consistent(choice);
  // The strategies that weigh candidates by their contribution: ris, or restir reusing its samples.
  EXPECT_TRUE(choice.options.kind == "ris" || choice.options.kind == "restir") << efficiencies(choice);
  EXPECT_EQ(choice.pilot_passes, kMinPilotPasses) << efficiencies(choice);  // far ahead: known at once
  EXPECT_GT(measure_of(choice, "ris").efficiency, 1.5 * measure_of(choice, "power").efficiency)
      << efficiencies(choice);
}

// restir is weighed on blocks of neighbouring pixels, against ris on the same pixels: where
// lights face many ways and only direct light is rendered, its reuse lowers ris's noise, at the
// cost of its target evaluations. Without scattering its reservoirs light nothing, and a render
// too short to pay for the blocks does not weigh it either.
TEST(StrategyChoice, ReuseIsWeighedOnBlocks) {
  RenderSettings long_render = settings();
  long_render.spp = 1024;  // the blocks paid for, on an image of 32 x 24
  const std::atomic<bool> cancel{true};  // the choice alone: no pass
  const StrategyChoice choice = Renderer(facing_away(), long_render).render({}, cancel).strategy_choice;
  EXPECT_GT(choice.pilot_block_pixels, 0u);
  const PilotMeasure &ris = measure_of(choice, "ris"), &restir = measure_of(choice, "restir");
  EXPECT_LT(restir.relative_variance, 0.8 * ris.relative_variance) << efficiencies(choice);
  EXPECT_GT(restir.targets_per_path, 1.0) << efficiencies(choice);
  EXPECT_GT(restir.cost, ris.cost) << efficiencies(choice);
  EXPECT_EQ(ris.targets_per_path, 0.0);

  RenderSettings direct = long_render;
  direct.max_depth = 0;
  for (const RenderSettings& s : {direct, settings()}) {  // no scattering; 2 passes
    const StrategyChoice without = Renderer(facing_away(), s).render({}, cancel).strategy_choice;
    EXPECT_EQ(without.pilot_block_pixels, 0u);
    EXPECT_THROW(measure_of(without, "restir"), std::runtime_error);
  }
}

TEST(StrategyChoice, CostDecides) {
  RenderSettings s = settings();
  s.strategy.lights = 1e5;
  const StrategyChoice choice = render(small_far_light(), s).strategy_choice;
  expect_consistent(choice);
  EXPECT_EQ(choice.options.kind, "power") << efficiencies(choice);
  EXPECT_LT(measure_of(choice, "trs").efficiency, 0.5 * measure_of(choice, "power").efficiency)
      << efficiencies(choice);
}

// The pilot's seeds are its own and its work is counted: every seed and thread count gives the
// same choice from the same figures, bit for bit.
TEST(StrategyChoice, TheSameForEverySeedAndThreadCount) {
  const Scene scene = sparse_panel();
  const StrategyChoice a = render(scene, settings(1, 2)).strategy_choice;
  for (const auto& [seed, threads] : {std::pair{2ull, 2u}, std::pair{1ull, 1u}}) {
    const StrategyChoice b = render(scene, settings(seed, threads)).strategy_choice;
    EXPECT_EQ(b.options.kind, a.options.kind);
    ASSERT_EQ(b.pilot.size(), a.pilot.size());
    for (std::size_t i = 0; i < a.pilot.size(); ++i) {
      EXPECT_EQ(b.pilot[i].relative_variance, a.pilot[i].relative_variance) << a.pilot[i].strategy;
      EXPECT_EQ(b.pilot[i].cost, a.pilot[i].cost) << a.pilot[i].strategy;
    }
    EXPECT_EQ(b.pilot_passes, a.pilot_passes);
    EXPECT_EQ(b.reason, a.reason);
  }
}

// The pilot spends at most kPilotShare of the render's paths beyond its least (kMinPilotPasses
// on a grid of about a thousand pixels): a render of 2 passes of 160 x 120 pixels gets a smaller
// grid than one of 64, and every pilot stays within its share once over that least. A pilot
// blind to the render's length would spend the same on both.
TEST(StrategyChoice, ThePilotSpendsItsShareOfTheRender) {
  const Scene scene = sparse_panel();
  const auto choice_at = [&](unsigned spp) {
    RenderSettings s = settings();
    s.width = 160;
    s.height = 120;
    s.spp = spp;
    s.strategy.lights = auto_lights(s.width, s.height, s.max_depth);
    const std::atomic<bool> cancel{true};  // the choice alone: no pass
    return Renderer(scene, s).render({}, cancel).strategy_choice;
  };
  const auto pilot_paths = [](const StrategyChoice& c) {
    return double(c.pilot_passes) * double(std::size(kPilotStrategies) * c.pilot_pixels + 2 * c.pilot_block_pixels);
  };
  const StrategyChoice short_render = choice_at(2), long_render = choice_at(64);
  expect_consistent(short_render);
  expect_consistent(long_render);
  EXPECT_EQ(short_render.pilot_passes, kMinPilotPasses);
  EXPECT_LT(short_render.pilot_pixels, long_render.pilot_pixels);
  EXPECT_LE(short_render.pilot_pixels, 1024u);
  EXPECT_LE(pilot_paths(long_render), kPilotShare * 64 * 160 * 120);
}

// To a deadline, a round of the pilot is weighed by its time against the time left: to one
// already past, a round costs more than any strategy could win back, and the pilot stops at its
// least; to one an hour away, a round costs next to nothing, and the pilot is the one of a
// render without a deadline (as long as its paths allow: spp unbounded), which here goes on
// beyond its least. A pilot blind to the deadline would run as long to both.
TEST(StrategyChoice, ToADeadlineThePilotWeighsARoundAgainstTheTimeLeft) {
  RenderSettings s = settings();
  s.spp = std::numeric_limits<unsigned>::max();
  const auto choice_to = [&](std::optional<std::chrono::steady_clock::time_point> deadline) {
    RenderSettings d = s;
    d.deadline = deadline;
    const std::atomic<bool> cancel{true};  // the choice alone: no pass
    return Renderer(sparse_panel(), d).render({}, cancel).strategy_choice;
  };
  const StrategyChoice unbounded = choice_to(std::nullopt);
  ASSERT_GT(unbounded.pilot_passes, kMinPilotPasses) << unbounded.reason;

  const StrategyChoice far = choice_to(std::chrono::steady_clock::now() + std::chrono::hours(1));
  EXPECT_EQ(far.pilot_passes, unbounded.pilot_passes);
  EXPECT_EQ(far.reason, unbounded.reason);

  const StrategyChoice past = choice_to(std::chrono::steady_clock::now());
  expect_consistent(past);
  EXPECT_EQ(past.pilot_passes, kMinPilotPasses) << past.reason;
  EXPECT_NE(past.reason.find("could win back"), std::string::npos) << past.reason;
}

// The pilot's paths stay out of the image: `auto` renders as the strategy it chose, bit for bit.
// The last case is a long render of the lights facing away, where the pilot weighs restir on
// blocks and takes it: two of its passes, reuse and all.
TEST(StrategyChoice, RendersAsTheStrategyItChose) {
  RenderSettings long_render = settings(3);
  long_render.spp = 1024;
  const std::atomic<bool> cancel{false};
  for (const auto& [scene, s] : {std::pair{sparse_panel(), settings(3)}, std::pair{facing_away(), settings(3)},
                                 std::pair{small_far_light(), settings(3)}, std::pair{facing_away(), long_render}}) {
    const RenderResult chosen = Renderer(scene, s).render_more(2, {}, cancel);
    RenderSettings named = s;
    named.strategy.kind = chosen.strategy_choice.options.kind;
    const RenderResult direct = Renderer(scene, named).render_more(2, {}, cancel);
    EXPECT_EQ(chosen.strategy, direct.strategy);
    EXPECT_EQ(chosen.rgb, direct.rgb) << chosen.strategy;
    EXPECT_TRUE(direct.strategy_choice.pilot.empty());
    if (s.spp == long_render.spp) EXPECT_EQ(chosen.strategy, "restir") << efficiencies(chosen.strategy_choice);
  }
}

}  // namespace
