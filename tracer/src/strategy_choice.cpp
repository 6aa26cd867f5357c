// `auto`: the strategy that renders the scene most efficiently, by measurement. Which one that
// is depends on what the texture, the lights' orientations and distances, the materials and the
// cost of each strategy make of the scene together (docs/noise.md, "The default chooses by a
// pilot"): drawing by the texels (trs) pays where the emission varies within the lights,
// weighing candidates by their contribution (ris) where lights face many ways, and the cheapest
// draw (power) where neither gains enough for its cost. A pilot renders a few passes of each
// over a grid of the image's pixels and keeps the one whose noise times work per pass is the
// least.
//
// The work is counted, not timed, so that the choice is the same on every run: rays traced,
// light samples weighed (each a draw and a BSDF evaluation) and the light sampler's tries, at
// unit costs in rays measured on this renderer (tools/pilot_costs.py).

#include "strategy_choice.h"

#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "luminance.h"
#include "pixel_ray.h"
#include "scene_io/relmse.h"
#include "tracer/path_random.h"
#include "tracer/path_tracer.h"
#include "tracer/strategy_registry.h"

namespace tracer {
namespace {

/// Points the texel gain is measured on; its relative error is well below a percent for any
/// emission whose texels vary by less than a few hundred times within a light.
constexpr double kGainSamples = 65536;
constexpr std::uint64_t kGainSeed = 0x7e4e1a9a1ull;

/// The pilot: this many passes of each strategy, over a grid of about kPilotPixels pixels.
constexpr unsigned kPilotPasses = 8;
constexpr double kPilotPixels = 4096;
constexpr std::uint64_t kPilotSeed = 0x70696c6f74ull;

/// Unit costs of the pilot's work, in rays (each a closest-hit or shadow ray with the shading
/// around it): a light sample weighed (drawn, and its BSDF evaluated), and a try of the light
/// sampler's rejection loop (its point written where kept). The medians of tools/pilot_costs.py
/// over the 17 shipped scenes and real assets (0.04 to 0.37, and 0.04 to 0.27, by scene).
constexpr double kPilotLightSampleCost = 0.15;
constexpr double kPilotSamplerTryCost = 0.10;

double texel_gain(Emitters& emitters) {
  lightsampler::Frame frame;
  lightsampler::FrameRequest request;
  request.seed = kGainSeed;
  request.target_count = kGainSamples;
  emitters.sampler().generate(request, frame);
  const std::span<const double> integrals = emitters.light_density();
  double sum = 0.0;
  std::uint64_t count = 0;
  for (const lightsampler::Sample& s : frame.samples.span()) {
    const double mean = integrals[s.triangle] / double(emitters.area(s.triangle));
    if (!(mean > 0.0) || !std::isfinite(mean)) continue;
    sum += double(emitters.density(s.triangle, s.b1, s.b2)) / mean;
    ++count;
  }
  return count > 0 ? sum / double(count) : 1.0;
}

/// The pilot's pixels: every `stride`-th of each row and column, from the middle of the first
/// stride (or the last pixel, where the image is narrower than half a stride).
struct PilotGrid {
  unsigned stride, x0, y0, columns, rows;

  PilotGrid(unsigned w, unsigned h)
      : stride(unsigned(std::max(1.0, std::ceil(std::sqrt(double(w) * h / kPilotPixels))))),
        x0(std::min(stride / 2, w - 1)),
        y0(std::min(stride / 2, h - 1)),
        columns((w - x0 + stride - 1) / stride),
        rows((h - y0 + stride - 1) / stride) {}
  std::size_t size() const { return std::size_t(columns) * rows; }
  unsigned x(std::size_t i) const { return x0 + unsigned(i % columns) * stride; }
  unsigned y(std::size_t i) const { return y0 + unsigned(i / columns) * stride; }
};

/// One strategy's pilot passes, pixel by pixel (kPilotPasses a pixel, one pixel after another):
/// each path's luminance, and the part of it the light strategy makes, and the work counted.
struct PilotRun {
  std::vector<double> luminance;
  /// Without the emission the camera rays met, whose noise is the same for every strategy: it
  /// would hide what they differ by where emitters fill the image.
  std::vector<double> lit;
  std::uint64_t rays = 0, light_queries = 0, sampler_tries = 0;
};

PilotRun run_pilot(LightStrategy& strategy, const PathTracer& tracer, const PinholeCamera& camera,
                   const PilotGrid& grid, unsigned width) {
  PilotRun run{std::vector<double>(grid.size() * kPilotPasses), std::vector<double>(grid.size() * kPilotPasses)};
  const lightsampler::PhiloxKey key = path_key(kPilotSeed);
  tbb::combinable<std::uint64_t> rays, queries;
  for (unsigned pass = 0; pass < kPilotPasses; ++pass) {
    strategy.begin_pass(pass_seed(kPilotSeed, pass));
    tbb::parallel_for(std::size_t(0), grid.size(), [&](std::size_t i) {
      const unsigned x = grid.x(i), y = grid.y(i);
      PathRandom random(key, y * width + x, pass);
      const PathEstimate e = tracer.radiance(pixel_ray(camera, x, y, random), random, rays.local());
      queries.local() += e.light_queries;
      const double l = luminance(e.radiance), seen = luminance(e.seen_emission);
      const bool finite = std::isfinite(l) && std::isfinite(seen);  // else black, as the renderer counts it
      run.luminance[i * kPilotPasses + pass] = finite ? l : 0.0;
      run.lit[i * kPilotPasses + pass] = finite ? l - seen : 0.0;
    });
    run.sampler_tries += strategy.last_pass().candidates;
  }
  run.rays = rays.combine(std::plus<>());
  run.light_queries = queries.combine(std::plus<>());
  return run;
}

/// Per pilot pixel, the weight of its variance in a pass's relMSE: 1 / (r^2 + guard), r the
/// median of every strategy's pilot paths there. The median, not the mean: a rare bright path
/// (a firefly) raises the mean of its own pixel and would hide the very variance it makes.
std::vector<double> noise_weights(const std::vector<PilotRun>& runs, std::size_t pixels) {
  std::vector<double> weights(pixels), values;
  for (std::size_t i = 0; i < pixels; ++i) {
    values.clear();
    for (const PilotRun& r : runs)
      values.insert(values.end(), r.luminance.begin() + i * kPilotPasses, r.luminance.begin() + (i + 1) * kPilotPasses);
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    const double median = values[values.size() / 2];
    weights[i] = 1.0 / (median * median + trs::kRelmseGuard);
  }
  return weights;
}

/// Fills `m`'s noise from its run: the weighted mean of its pixels' variances.
void measure_noise(const PilotRun& run, const std::vector<double>& weights, PilotMeasure& m) {
  constexpr double n = kPilotPasses;
  double sum = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    double s = 0.0, squares = 0.0;
    for (unsigned k = 0; k < kPilotPasses; ++k) {
      const double l = run.lit[i * kPilotPasses + k];
      s += l;
      squares += l * l;
    }
    sum += weights[i] * std::max(0.0, (squares - s * s / n) / (n - 1.0));
  }
  m.relative_variance = sum / double(weights.size());
}

/// Fills `m`'s cost from its run: the work of a pass over `pixels`, the light sampler's tries
/// scaled from the pilot's lights to the render's.
void measure_cost(const PilotRun& run, unsigned candidates, std::size_t paths, double lights_scale,
                  std::size_t pixels, PilotMeasure& m) {
  m.rays_per_path = double(run.rays) / double(paths);
  m.light_samples_per_path = double(run.light_queries) * candidates / double(paths);
  m.sampler_tries_per_pass = double(run.sampler_tries) * lights_scale / kPilotPasses;
  m.cost = double(pixels) * (m.rays_per_path + kPilotLightSampleCost * m.light_samples_per_path) +
           kPilotSamplerTryCost * m.sampler_tries_per_pass;
}

std::string pilot_reason(const std::vector<PilotMeasure>& pilot, const PilotMeasure& best, const PilotGrid& grid) {
  char text[512];
  int n = std::snprintf(text, sizeof text,
                        "a pilot of %u passes on %zu pixels: %s renders most efficiently (relative variance %.3g a pass, "
                        "cost %.3g rays a pass)",
                        kPilotPasses, grid.size(), best.strategy.c_str(), best.relative_variance, best.cost);
  for (const PilotMeasure& m : pilot)
    if (&m != &best && n > 0 && std::size_t(n) < sizeof text)
      n += std::snprintf(text + n, sizeof text - n, "; %s %.2fx as efficient", m.strategy.c_str(),
                         m.efficiency / best.efficiency);
  return text;
}

}  // namespace

ChosenStrategy choose_strategy(const Scene& scene, const Geometry& geometry, Emitters& emitters,
                               const PinholeCamera& camera, const RenderSettings& settings) {
  const StrategyOptions& options = settings.strategy;
  if (options.kind != kAutoStrategy) {
    // Made before the aggregate: GCC 12 destroys a braced return value's members twice when one
    // of them throws as it is built.
    std::unique_ptr<LightStrategy> strategy = make_light_strategy(emitters, options);
    return {{options, 0.0, {}, {}}, std::move(strategy)};
  }
  const auto start = std::chrono::steady_clock::now();
  ChosenStrategy chosen{{options, 1.0, {}, {}}, nullptr};
  StrategyChoice& choice = chosen.choice;
  if (emitters.count() == 0 || !(emitters.total_density() > 0.0)) {  // nothing to draw by texels or to weigh
    choice.options.kind = "power";
    choice.reason = emitters.count() == 0 ? "the scene's lights are punctual alone: power"
                                          : "no emissive texel emits at this frame: power";
    chosen.strategy = make_light_strategy(emitters, choice.options);
    return chosen;
  }
  choice.texel_gain = texel_gain(emitters);

  std::optional<tbb::global_control> limit;
  if (settings.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, settings.threads);
  const PilotGrid grid(settings.width, settings.height);
  const std::size_t pixels = std::size_t(settings.width) * settings.height;
  // A pass's point lights in proportion to the pilot's pixels: a connection picks one light of
  // the set, so the noise per path is the same (renderer.h, kAutoLightsPerQuery).
  const double lights_share = double(grid.size()) / double(pixels);
  std::vector<PilotRun> runs;
  for (const char* kind : kPilotStrategies) {
    StrategyOptions o = options;
    o.kind = kind;
    o.lights = std::max(1.0, std::round(options.lights * lights_share));
    const std::unique_ptr<LightStrategy> strategy = make_light_strategy(emitters, o);
    const PathTracer tracer(scene, geometry, emitters, *strategy, settings.max_depth);
    runs.push_back(run_pilot(*strategy, tracer, camera, grid, settings.width));
    choice.pilot.push_back({kind});
    measure_cost(runs.back(), strategy->candidates(), grid.size() * kPilotPasses, options.lights / o.lights, pixels,
                 choice.pilot.back());
  }
  const std::vector<double> weights = noise_weights(runs, grid.size());
  // A floor on the noise keeps the efficiency finite where a strategy's pilot saw none (a black
  // image): the cheapest then wins.
  constexpr double kNoiseFloor = 1e-30;
  for (std::size_t s = 0; s < runs.size(); ++s) {
    PilotMeasure& m = choice.pilot[s];
    measure_noise(runs[s], weights, m);
    m.efficiency = 1.0 / (std::max(m.relative_variance, kNoiseFloor) * m.cost);
  }
  // The first of the most efficient, in kPilotStrategies' order (the cheapest first) on a tie.
  std::size_t best = 0;
  for (std::size_t s = 1; s < runs.size(); ++s)
    if (choice.pilot[s].efficiency > choice.pilot[best].efficiency) best = s;
  choice.options.kind = choice.pilot[best].strategy;
  choice.reason = pilot_reason(choice.pilot, choice.pilot[best], grid);
  chosen.strategy = make_light_strategy(emitters, choice.options);  // with the render's lights
  chosen.pilot_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return chosen;
}

}  // namespace tracer
