// `auto`: the strategy that renders the scene most efficiently, by measurement. Which one that
// is depends on what the texture, the lights' orientations and distances, the materials and the
// cost of each strategy make of the scene together (docs/noise.md, "The default chooses by a
// pilot"): drawing by the texels (trs) pays where the emission varies within the lights,
// weighing candidates by their contribution (ris) where lights face many ways, and the cheapest
// draw (power) where neither gains enough for its cost. A pilot renders a few passes of each
// over a grid of the image's pixels, and the cheapest of those whose noise times work per pass
// is within kCheaperMargin of the least renders.
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
#include <numeric>
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

/// The pilot's grid: about this many of the image's pixels, fewer where kPilotShare of a short
/// render does not pay for as many, but not fewer than kMinPilotPixels (light_strategy.h gives
/// its passes).
constexpr double kPilotPixels = 4096, kMinPilotPixels = 1024;
constexpr std::uint64_t kPilotSeed = 0x70696c6f74ull;

/// Unit costs of the pilot's work, in rays (each a closest-hit or shadow ray with the shading
/// around it): a light sample weighed, by strategy in kPilotStrategies' order, and a try of the
/// light sampler's rejection loop (its point written where kept). A `power` sample draws a point
/// on a triangle and reads the textures there; a `trs` or `ris` one picks a point light whose
/// record carries its radiance, and `ris` evaluates each candidate's contribution. Fitted by
/// tools/pilot_costs.py over the shipped scenes and real assets: the light samples' over all of
/// them together, the try's the median of the scenes' (0.08 to 0.53 by scene). A light sample
/// and a ray trade off within a scene, so the samples' level is only roughly known (half to
/// twice these, with the scenes resampled), but how a pass of one strategy compares with another's,
/// which decides, is known to a few percent.
constexpr double kPilotLightSampleCost[] = {1.53, 1.15, 0.56};
static_assert(std::size(kPilotLightSampleCost) == std::size(kPilotStrategies));
constexpr double kPilotSamplerTryCost = 0.17;

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

  /// About `pixels` of a w x h image.
  PilotGrid(unsigned w, unsigned h, double pixels)
      : stride(unsigned(std::max(1.0, std::ceil(std::sqrt(double(w) * h / pixels))))),
        x0(std::min(stride / 2, w - 1)),
        y0(std::min(stride / 2, h - 1)),
        columns((w - x0 + stride - 1) / stride),
        rows((h - y0 + stride - 1) / stride) {}
  std::size_t size() const { return std::size_t(columns) * rows; }
  unsigned x(std::size_t i) const { return x0 + unsigned(i % columns) * stride; }
  unsigned y(std::size_t i) const { return y0 + unsigned(i / columns) * stride; }
};

/// One strategy's pilot: its paths' luminances, pixel by pixel (kMaxPilotPasses a pixel, in pass
/// order), the part of each the light strategy makes, and the work counted.
struct PilotRun {
  std::unique_ptr<LightStrategy> strategy;
  double lights = 0.0;  ///< the point lights of its passes, in proportion to the grid's pixels
  std::optional<PathTracer> tracer;
  std::vector<double> luminance;
  /// Without the emission the camera rays met, whose noise is the same for every strategy: it
  /// would hide what they differ by where emitters fill the image.
  std::vector<double> lit;
  std::uint64_t rays = 0, light_queries = 0, sampler_tries = 0;
  double light_sample_cost = 0.0;  ///< in rays (kPilotLightSampleCost)
};

/// Renders passes [first, last) of `run`'s strategy over the grid.
void run_passes(PilotRun& run, const PinholeCamera& camera, const PilotGrid& grid, unsigned width, unsigned first,
                unsigned last) {
  const lightsampler::PhiloxKey key = path_key(kPilotSeed);
  tbb::combinable<std::uint64_t> rays, queries;
  for (unsigned pass = first; pass < last; ++pass) {
    run.strategy->begin_pass(pass_seed(kPilotSeed, pass));
    tbb::parallel_for(std::size_t(0), grid.size(), [&](std::size_t i) {
      const unsigned x = grid.x(i), y = grid.y(i);
      PathRandom random(key, y * width + x, pass);
      const PathEstimate e = run.tracer->radiance(pixel_ray(camera, x, y, random), random, rays.local());
      queries.local() += e.light_queries;
      const double l = luminance(e.radiance), seen = luminance(e.seen_emission);
      const bool finite = std::isfinite(l) && std::isfinite(seen);  // else black, as the renderer counts it
      run.luminance[i * kMaxPilotPasses + pass] = finite ? l : 0.0;
      run.lit[i * kMaxPilotPasses + pass] = finite ? l - seen : 0.0;
    });
    run.sampler_tries += run.strategy->last_pass().candidates;
  }
  run.rays += rays.combine(std::plus<>());
  run.light_queries += queries.combine(std::plus<>());
}

/// Per pilot pixel, the weight of its variance in a pass's relMSE: 1 / (r^2 + guard), r the
/// median of every strategy's pilot paths there. The median, not the mean: a rare bright path
/// (a firefly) raises the mean of its own pixel and would hide the very variance it makes.
std::vector<double> noise_weights(const std::vector<PilotRun>& runs, std::size_t pixels, unsigned passes) {
  std::vector<double> weights(pixels), values;
  for (std::size_t i = 0; i < pixels; ++i) {
    values.clear();
    for (const PilotRun& r : runs) {
      const auto first = r.luminance.begin() + std::ptrdiff_t(i * kMaxPilotPasses);
      values.insert(values.end(), first, first + passes);
    }
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    const double median = values[values.size() / 2];
    weights[i] = 1.0 / (median * median + trs::kRelmseGuard);
  }
  return weights;
}

/// Each pilot pixel's weighted variance over the first `passes` passes of `run`.
std::vector<double> pixel_noise(const PilotRun& run, const std::vector<double>& weights, unsigned passes) {
  std::vector<double> noise(weights.size());
  for (std::size_t i = 0; i < weights.size(); ++i) {
    double s = 0.0, squares = 0.0;
    for (unsigned k = 0; k < passes; ++k) {
      const double l = run.lit[i * kMaxPilotPasses + k];
      s += l;
      squares += l * l;
    }
    noise[i] = weights[i] * std::max(0.0, (squares - s * s / passes) / (passes - 1.0));
  }
  return noise;
}

/// The standard error, over the pilot's pixels, of the log of the ratio of the means of `a` and
/// `b` (the delta method). The pixels are paired: the strategies' paths there share their seeds
/// and what makes a pixel hard, so their noises mostly move together, and the ratio is usually
/// better known than either.
double log_ratio_error(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  const double mean_a = std::accumulate(a.begin(), a.end(), 0.0) / n;
  const double mean_b = std::accumulate(b.begin(), b.end(), 0.0) / n;
  if (!(mean_a > 0.0) || !(mean_b > 0.0) || a.size() < 2) return 0.0;
  double sum = 0.0, squares = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = a[i] / mean_a - b[i] / mean_b;
    sum += d;
    squares += d * d;
  }
  return std::sqrt(std::max(0.0, squares - sum * sum / n) / (n - 1.0) / n);
}

/// Fills `m`'s cost from its run: the work of a pass over `pixels`, the light sampler's tries
/// scaled from the pilot's lights to the render's.
void measure_cost(const PilotRun& run, unsigned passes, std::size_t grid_pixels, double lights_scale,
                  std::size_t pixels, PilotMeasure& m) {
  const double paths = double(grid_pixels) * passes;
  m.rays_per_path = double(run.rays) / paths;
  m.light_samples_per_path = double(run.light_queries) * run.strategy->candidates() / paths;
  m.sampler_tries_per_pass = double(run.sampler_tries) * lights_scale / passes;
  m.cost = double(pixels) * (m.rays_per_path + run.light_sample_cost * m.light_samples_per_path) +
           kPilotSamplerTryCost * m.sampler_tries_per_pass;
}

/// Fills each strategy's measure from the first `passes` passes of its run, its cost for a pass
/// of `render_lights` point lights over `pixels`; returns each one's noise, pixel by pixel.
std::vector<std::vector<double>> measure_pilot(const std::vector<PilotRun>& runs, unsigned passes,
                                               double render_lights, std::size_t pixels,
                                               std::vector<PilotMeasure>& pilot) {
  // A floor on the noise keeps the efficiency finite where a strategy's pilot saw none (a black
  // image): the cheapest then wins.
  constexpr double kNoiseFloor = 1e-30;
  const std::size_t grid_pixels = runs.front().lit.size() / kMaxPilotPasses;
  const std::vector<double> weights = noise_weights(runs, grid_pixels, passes);
  std::vector<std::vector<double>> noise;
  for (std::size_t s = 0; s < runs.size(); ++s) {
    PilotMeasure& m = pilot[s];
    measure_cost(runs[s], passes, grid_pixels, render_lights / runs[s].lights, pixels, m);
    noise.push_back(pixel_noise(runs[s], weights, passes));
    m.relative_variance = std::accumulate(noise[s].begin(), noise[s].end(), 0.0) / double(grid_pixels);
    m.efficiency = 1.0 / (std::max(m.relative_variance, kNoiseFloor) * m.cost);
  }
  return noise;
}

/// The most efficient strategy; the first, in kPilotStrategies' order (the cheapest first), on a tie.
std::size_t leader(const std::vector<PilotMeasure>& pilot) {
  std::size_t best = 0;
  for (std::size_t s = 1; s < pilot.size(); ++s)
    if (pilot[s].efficiency > pilot[best].efficiency) best = s;
  return best;
}

/// The strategy that renders: the cheapest of those within kCheaperMargin of the most efficient,
/// `best` (itself where none is cheaper).
std::size_t cheapest_close_to(const std::vector<PilotMeasure>& pilot, std::size_t best) {
  std::size_t chosen = best;
  for (std::size_t s = 0; s < pilot.size(); ++s)
    if (pilot[s].efficiency >= (1.0 - kCheaperMargin) * pilot[best].efficiency && pilot[s].cost < pilot[chosen].cost)
      chosen = s;
  return chosen;
}

/// Fills each strategy's relative_error: that of the ratio of its noise to the leader's, `best`.
void measure_errors(std::vector<PilotMeasure>& pilot, const std::vector<std::vector<double>>& noise, std::size_t best) {
  for (std::size_t s = 0; s < pilot.size(); ++s) pilot[s].relative_error = log_ratio_error(noise[s], noise[best]);
}

/// Whether no other strategy can be more than kPilotIndifference more efficient than the leader,
/// by kPilotStandardErrors of its relative_error (the costs are counted, not sampled).
bool decided(const std::vector<PilotMeasure>& pilot, std::size_t best) {
  for (std::size_t s = 0; s < pilot.size(); ++s) {
    if (s == best) continue;
    const double margin = kPilotStandardErrors * pilot[s].relative_error;
    if (std::log(pilot[s].efficiency / pilot[best].efficiency) + margin > std::log1p(kPilotIndifference)) return false;
  }
  return true;
}

std::string pilot_reason(const std::vector<PilotMeasure>& pilot, std::size_t best, std::size_t chosen,
                         const PilotGrid& grid, unsigned passes, const char* stop) {
  char text[640];
  const PilotMeasure& b = pilot[best];
  int n = std::snprintf(text, sizeof text,
                        "a pilot of %u passes%s on %zu pixels: %s is the most efficient (relative variance %.3g a "
                        "pass, cost %.3g rays a pass)",
                        passes, stop, grid.size(), b.strategy.c_str(), b.relative_variance, b.cost);
  for (const PilotMeasure& m : pilot)
    if (&m != &b && n > 0 && std::size_t(n) < sizeof text)
      n += std::snprintf(text + n, sizeof text - n, "; %s %.2fx as efficient", m.strategy.c_str(),
                         m.efficiency / b.efficiency);
  if (n > 0 && std::size_t(n) < sizeof text)
    std::snprintf(text + n, sizeof text - n, "; %s renders, as the cheapest within %.0f%% of it", pilot[chosen].strategy.c_str(),
                  100.0 * kCheaperMargin);
  return text;
}

}  // namespace

std::size_t strategy_to_render(const std::vector<PilotMeasure>& pilot) {
  return pilot.empty() ? 0 : cheapest_close_to(pilot, leader(pilot));
}

bool pilot_decided(std::vector<PilotMeasure> pilot, const std::vector<std::vector<double>>& noise) {
  if (pilot.empty()) return true;
  const std::size_t best = leader(pilot);
  measure_errors(pilot, noise, best);
  return decided(pilot, best);
}

ChosenStrategy choose_strategy(const Scene& scene, const Geometry& geometry, Emitters& emitters,
                               const PinholeCamera& camera, const RenderSettings& settings) {
  const StrategyOptions& options = settings.strategy;
  ChosenStrategy chosen;
  StrategyChoice& choice = chosen.choice;
  choice.options = options;
  if (options.kind != kAutoStrategy) {
    chosen.strategy = make_light_strategy(emitters, options);
    return chosen;
  }
  const auto start = std::chrono::steady_clock::now();
  choice.texel_gain = 1.0;
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
  const std::size_t pixels = std::size_t(settings.width) * settings.height;
  const std::size_t strategies = std::size(kPilotStrategies);
  // The pilot's paths: at most kPilotShare of the render's, but kMinPilotPasses on at least
  // kMinPilotPixels.
  const double budget = kPilotShare * double(settings.spp) * double(pixels);
  const PilotGrid grid(settings.width, settings.height,
                       std::clamp(budget / double(strategies * kMinPilotPasses), kMinPilotPixels, kPilotPixels));
  const auto within_budget = [&](unsigned passes) { return double(passes * strategies * grid.size()) <= budget; };
  // A pass's point lights in proportion to the pilot's pixels: a connection picks one light of
  // the set, so the noise per path is the same (renderer.h, kAutoLightsPerQuery).
  const double lights_share = double(grid.size()) / double(pixels);
  std::vector<PilotRun> runs(strategies);
  for (std::size_t s = 0; s < runs.size(); ++s) {
    StrategyOptions o = options;
    o.kind = kPilotStrategies[s];
    o.lights = std::max(1.0, std::round(options.lights * lights_share));
    runs[s].lights = o.lights;
    runs[s].light_sample_cost = kPilotLightSampleCost[s];
    runs[s].strategy = make_light_strategy(emitters, o);
    runs[s].tracer.emplace(scene, geometry, emitters, *runs[s].strategy, settings.max_depth);
    runs[s].luminance.resize(grid.size() * kMaxPilotPasses);
    runs[s].lit.resize(grid.size() * kMaxPilotPasses);
    choice.pilot.push_back({o.kind});
  }
  std::size_t best = 0;
  unsigned passes = 0;
  bool knew = false;  // whether it stopped because no other strategy can be far ahead
  while (passes < kMaxPilotPasses) {
    for (PilotRun& run : runs) run_passes(run, camera, grid, settings.width, passes, passes + kPilotRoundPasses);
    passes += kPilotRoundPasses;
    if (passes < kMinPilotPasses) continue;
    const std::vector<std::vector<double>> noise = measure_pilot(runs, passes, options.lights, pixels, choice.pilot);
    best = leader(choice.pilot);
    measure_errors(choice.pilot, noise, best);
    knew = decided(choice.pilot, best);
    if (knew || !within_budget(passes + kPilotRoundPasses)) break;
  }
  const std::size_t rendering = cheapest_close_to(choice.pilot, best);
  choice.pilot_passes = passes;
  choice.pilot_pixels = grid.size();
  choice.most_efficient = choice.pilot[best].strategy;
  choice.options.kind = choice.pilot[rendering].strategy;
  const char* stop = knew ? "" : passes == kMaxPilotPasses ? " (its most)" : " (its share of the render)";
  choice.reason = pilot_reason(choice.pilot, best, rendering, grid, passes, stop);
  chosen.strategy = make_light_strategy(emitters, choice.options);  // with the render's lights
  chosen.pilot_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return chosen;
}

}  // namespace tracer
