// `auto`: the strategy that renders the scene most efficiently, by measurement. Which one that
// is depends on what the texture, the lights' orientations and distances, the materials and the
// cost of each strategy make of the scene together (docs/noise.md, "The default chooses by a
// pilot"): drawing by the texels (trs) pays where the emission varies within the lights,
// weighing candidates by their contribution (ris) where lights face many ways, and the cheapest
// draw (power) where neither gains enough for its cost. A pilot renders a few passes of each
// over a grid of the image's pixels, and `restir` and `ris` a few over blocks of neighbouring
// pixels, whose reuse restir needs; the cheapest of those whose noise times work per pass is
// within kCheaperMargin of the least renders.
//
// The work is counted, not timed, so that the choice is the same on every run: rays traced,
// light samples weighed (each a draw and a BSDF evaluation), restir's evaluations of its
// target and the light sampler's tries, at unit costs in rays measured on this renderer
// (tools/pilot_costs.py).

#include "strategy_choice.h"

#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>

#include "luminance.h"
#include "pixel_ray.h"
#include "reuse.h"
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
/// restir's reuse, in rays: a reservoir gathered (its camera ray's first surface shaded and kept,
/// beside the ray itself and its candidates, which count as such), and an evaluation of its
/// target at a surface (a light point seen from it and its BSDF). Fitted by
/// tools/pilot_costs.py (--light-sample-costs as above) to restir's whole pass over the shipped
/// scenes and real assets: within 11% of it on most, 21 and 23% under on two, 30% over on one.
constexpr double kPilotReservoirCost = 1.34, kPilotTargetCost = 0.67;

/// restir's blocks: up to kPilotBlocks squares of kPilotBlockSide pixels, drawn where the grid's
/// first passes saw noise (block_centres). Twice restir's default radius across, so that most of
/// a pixel's neighbours are in its block. They take at most kPilotBlockShare of the pilot's least
/// paths; a render too short to pay for kMinPilotBlocks, whose spread tells how well the blocks
/// know restir, does not weigh it.
constexpr unsigned kPilotBlockSide = 16, kPilotBlocks = 8, kMinPilotBlocks = 3;
constexpr double kPilotBlockShare = 0.25;

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

/// Pixels of the image the pilot renders, row by row of a `width` x `height` image of their own,
/// in which restir's reuse finds their neighbours.
struct PilotPixels {
  unsigned width = 0, height = 0;
  unsigned block_side = 0;  ///< restir's blocks': `block_side` square each, side by side; 0: a grid
  std::vector<unsigned> x, y;  ///< each one's place in the render's image

  /// Per pixel, the weight of its noise in the pilot's mean (empty: 1 each): restir's blocks are
  /// drawn where the grid saw noise, and weighted back (block_centres).
  std::vector<double> importance;

  std::size_t size() const { return x.size(); }
  void add(unsigned px, unsigned py) {
    x.push_back(px);
    y.push_back(py);
  }
};

/// About `pixels` of a w x h image: every `stride`-th of each row and column, from the middle of
/// the first stride (or the last pixel, where the image is narrower than half a stride).
PilotPixels pilot_grid(unsigned w, unsigned h, double pixels) {
  const unsigned stride = unsigned(std::max(1.0, std::ceil(std::sqrt(double(w) * h / pixels))));
  const unsigned x0 = std::min(stride / 2, w - 1), y0 = std::min(stride / 2, h - 1);
  PilotPixels grid;
  grid.width = (w - x0 + stride - 1) / stride;
  grid.height = (h - y0 + stride - 1) / stride;
  for (unsigned j = 0; j < grid.height; ++j)
    for (unsigned i = 0; i < grid.width; ++i) grid.add(x0 + i * stride, y0 + j * stride);
  return grid;
}

/// restir's blocks, `side` pixels square, centred on `centres` and clamped into the w x h image,
/// side by side in the pilot's own image. A pixel's reuse finds its neighbours as in the render
/// but at its block's edges, where it meets another block's pixels and mostly turns them down as
/// another surface: if anything, the pilot sees restir a little noisier than it renders. Each
/// pixel's importance is its block's (BlockCentre).
struct BlockCentre {
  unsigned x, y;
  double importance;  ///< 1 / (the chance it was drawn times the grid's pixels)
};
PilotPixels pilot_blocks(unsigned w, unsigned h, unsigned side, const std::vector<BlockCentre>& centres) {
  PilotPixels blocks;
  blocks.width = side * unsigned(centres.size());
  blocks.height = side;
  blocks.block_side = side;
  const auto start = [side](unsigned centre, unsigned extent) { return std::min(centre - std::min(centre, side / 2), extent - side); };
  for (unsigned py = 0; py < side; ++py)
    for (const BlockCentre& c : centres)
      for (unsigned px = 0; px < side; ++px) {
        blocks.add(start(c.x, w) + px, start(c.y, h) + py);
        blocks.importance.push_back(c.importance);
      }
  return blocks;
}

/// One strategy's pilot: its paths' luminances, pixel by pixel (kMaxPilotPasses a pixel, in pass
/// order), the part of each the light strategy makes, and the work counted.
struct PilotRun {
  const PilotPixels* pixels = nullptr;
  std::unique_ptr<LightStrategy> strategy;
  double lights = 0.0;  ///< the point lights of its passes, in proportion to its pixels
  std::optional<PathTracer> tracer;
  std::optional<Reuse> reuse;  ///< restir's
  std::vector<double> luminance;
  /// Without the emission the camera rays met, whose noise is the same for every strategy: it
  /// would hide what they differ by where emitters fill the image.
  std::vector<double> lit;
  /// Per pixel, its work over the passes: kept apart so that the blocks' pixels can be weighted
  /// back (PilotPixels::importance), and summed in one order, the same on every run.
  struct Work {
    std::uint64_t rays = 0, light_queries = 0;
    ReuseWork reuse;
  };
  std::vector<Work> work;
  std::uint64_t sampler_tries = 0;
  double light_sample_cost = 0.0;  ///< in rays (kPilotLightSampleCost)
};

/// Gathers and combines restir's reservoirs over `run`'s pixels, for pass `pass`.
void reuse_pass(PilotRun& run, const PinholeCamera& camera, unsigned width, unsigned pass) {
  const PilotPixels& pixels = *run.pixels;
  const lightsampler::PhiloxKey key = path_key(kPilotSeed), gather_key = path_key(kPilotSeed ^ kGatherStream),
                                spatial_key = path_key(kPilotSeed ^ kSpatialStream);
  run.reuse->begin_pass();
  tbb::parallel_for(std::size_t(0), pixels.size(), [&](std::size_t i) {
    const unsigned x = pixels.x[i], y = pixels.y[i];
    PathRandom path(key, y * width + x, pass), random(gather_key, y * width + x, pass);
    PilotRun::Work& work = run.work[i];
    run.reuse->gather(std::uint32_t(i), pixel_ray(camera, x, y, path), random, work.rays, work.reuse);
  });
  tbb::parallel_for(std::size_t(0), pixels.size(), [&](std::size_t i) {
    PathRandom random(spatial_key, pixels.y[i] * width + pixels.x[i], pass);
    run.reuse->spatial(std::uint32_t(i), random, run.work[i].reuse);
  });
}

/// Renders passes [first, last) of `run`'s strategy over its pixels.
void run_passes(PilotRun& run, const PinholeCamera& camera, unsigned width, unsigned first, unsigned last) {
  const PilotPixels& pixels = *run.pixels;
  const lightsampler::PhiloxKey key = path_key(kPilotSeed);
  for (unsigned pass = first; pass < last; ++pass) {
    run.strategy->begin_pass(pass_seed(kPilotSeed, pass));
    if (run.reuse) reuse_pass(run, camera, width, pass);
    tbb::parallel_for(std::size_t(0), pixels.size(), [&](std::size_t i) {
      const unsigned x = pixels.x[i], y = pixels.y[i];
      PathRandom random(key, y * width + x, pass);
      std::optional<PathTracer::FirstSurface> reused;
      if (run.reuse) reused = run.reuse->first_surface(std::uint32_t(i));
      PilotRun::Work& work = run.work[i];
      const PathEstimate e =
          run.tracer->radiance(pixel_ray(camera, x, y, random), random, work.rays, reused ? &*reused : nullptr);
      work.light_queries += e.light_queries;
      const double l = luminance(e.radiance), seen = luminance(e.seen_emission);
      const bool finite = std::isfinite(l) && std::isfinite(seen);  // else black, as the renderer counts it
      run.luminance[i * kMaxPilotPasses + pass] = finite ? l : 0.0;
      run.lit[i * kMaxPilotPasses + pass] = finite ? l - seen : 0.0;
    });
    run.sampler_tries += run.strategy->last_pass().candidates;
  }
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
    if (!runs.front().pixels->importance.empty()) weights[i] *= runs.front().pixels->importance[i];
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

/// Where restir's blocks go: `count` of the grid's pixels, drawn (systematically, so the same
/// every run) in proportion to an even mixture of `run`'s noise there over its first `passes`
/// passes and a uniform share, so that the blocks go where the noise is but any pixel may get
/// one; each weighted back by the inverse of its chance, which keeps the blocks' mean an estimate
/// of the image's.
std::vector<BlockCentre> block_centres(const std::vector<PilotRun>& runs, const PilotRun& run, unsigned passes,
                                       unsigned count) {
  const PilotPixels& grid = *run.pixels;
  const std::vector<double> noise = pixel_noise(run, noise_weights(runs, grid.size(), passes), passes);
  const double total = std::accumulate(noise.begin(), noise.end(), 0.0), n = double(grid.size());
  std::vector<double> chance(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i)
    chance[i] = total > 0.0 ? 0.5 * noise[i] / total + 0.5 / n : 1.0 / n;
  std::vector<BlockCentre> centres;
  double cumulative = 0.0;
  std::size_t i = 0;
  for (unsigned k = 0; k < count; ++k) {
    const double u = (k + 0.5) / count;
    while (i + 1 < grid.size() && cumulative + chance[i] <= u) cumulative += chance[i++];
    centres.push_back({grid.x[i], grid.y[i], 1.0 / (chance[i] * n)});
  }
  return centres;
}

/// The standard error, over the pilot's pixels, of the log of the ratio of the sums of `a` and
/// `b`, by the jackknife: the spread of that log with each pixel left out in turn. The pixels
/// are paired: the strategies' paths there share their seeds and what makes a pixel hard, so
/// their noises mostly move together, and the ratio is usually better known than either. Where
/// one pixel holds most of both sums (a rare bright path in each), their ratio is that of two
/// fireflies, and leaving it out shows it; the delta method, which weighs each pixel by its
/// share of both sums alike, would take such a ratio as known. Infinite where leaving a pixel
/// out leaves nothing of a sum: the ratio rests on that pixel alone.
double log_ratio_error(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  const double sum_a = std::accumulate(a.begin(), a.end(), 0.0), sum_b = std::accumulate(b.begin(), b.end(), 0.0);
  if (!(sum_a > 0.0) || !(sum_b > 0.0) || n < 2) return 0.0;
  std::vector<double> left_out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double rest_a = sum_a - a[i], rest_b = sum_b - b[i];
    if (!(rest_a > 1e-12 * sum_a) || !(rest_b > 1e-12 * sum_b)) return std::numeric_limits<double>::infinity();
    left_out[i] = std::log(rest_a / rest_b);
  }
  const double mean = std::accumulate(left_out.begin(), left_out.end(), 0.0) / double(n);
  double squares = 0.0;
  for (const double v : left_out) squares += (v - mean) * (v - mean);
  return std::sqrt(squares * double(n - 1) / double(n));
}

/// Fills `m`'s cost from its run: the work of a pass over `pixels`, the light sampler's tries
/// scaled from the pilot's lights to the render's.
void measure_cost(const PilotRun& run, unsigned passes, double lights_scale, std::size_t pixels, PilotMeasure& m) {
  const std::vector<double>& importance = run.pixels->importance;
  double paths = 0.0, rays = 0.0, samples = 0.0, reservoirs = 0.0, targets = 0.0;
  for (std::size_t i = 0; i < run.work.size(); ++i) {
    const PilotRun::Work& w = run.work[i];
    const double weight = importance.empty() ? 1.0 : importance[i];
    paths += weight * passes;
    rays += weight * double(w.rays);
    samples += weight * (double(w.light_queries) * run.strategy->candidates() + double(w.reuse.candidates));
    reservoirs += weight * double(w.reuse.reservoirs);
    targets += weight * double(w.reuse.targets);
  }
  m.rays_per_path = rays / paths;
  m.light_samples_per_path = samples / paths;
  m.targets_per_path = targets / paths;
  m.sampler_tries_per_pass = double(run.sampler_tries) * lights_scale / passes;
  m.cost = double(pixels) * (m.rays_per_path + run.light_sample_cost * m.light_samples_per_path +
                             kPilotReservoirCost * reservoirs / paths + kPilotTargetCost * m.targets_per_path) +
           kPilotSamplerTryCost * m.sampler_tries_per_pass;
}

/// A floor on the noise keeps the efficiency finite where a strategy's pilot saw none (a black
/// image): the cheapest then wins.
constexpr double kNoiseFloor = 1e-30;

/// Fills each strategy's measure from the first `passes` passes of its run, its cost for a pass
/// of `render_lights` point lights over `pixels`; returns each one's noise, pixel by pixel.
std::vector<std::vector<double>> measure_pilot(const std::vector<PilotRun>& runs, unsigned passes,
                                               double render_lights, std::size_t pixels,
                                               std::vector<PilotMeasure>& pilot) {
  const std::size_t run_pixels = runs.front().lit.size() / kMaxPilotPasses;
  const std::vector<double> weights = noise_weights(runs, run_pixels, passes);
  std::vector<std::vector<double>> noise;
  for (std::size_t s = 0; s < runs.size(); ++s) {
    PilotMeasure& m = pilot[s];
    measure_cost(runs[s], passes, render_lights / runs[s].lights, pixels, m);
    noise.push_back(pixel_noise(runs[s], weights, passes));
    m.relative_variance = std::accumulate(noise[s].begin(), noise[s].end(), 0.0) / double(run_pixels);
    m.efficiency = 1.0 / (std::max(m.relative_variance, kNoiseFloor) * m.cost);
  }
  return noise;
}

/// Each block's sum of `noise`, a pixel's each, on `blocks`.
std::vector<double> block_sums(const std::vector<double>& noise, const PilotPixels& blocks) {
  std::vector<double> sums(blocks.width / blocks.block_side, 0.0);
  for (std::size_t i = 0; i < noise.size(); ++i) sums[(i % blocks.width) / blocks.block_side] += noise[i];
  return sums;
}

/// kPilotReuse's measure: its noise over kPilotReused's on the blocks, `pair` (theirs in that
/// order), times kPilotReused's on the grid, `reused`; its own cost. The blocks are few, and the
/// ratio varies from one to the next: it is taken kPilotStandardErrors of `error` (the standard
/// error of its log) above its estimate, so that restir, the dearest, renders only where the
/// pilot knows it leads as surely as the pilot's stop knows anything.
PilotMeasure reuse_measure(const PilotMeasure& reused, const std::vector<PilotMeasure>& pair, double error) {
  PilotMeasure m = pair[1];
  m.relative_variance = reused.relative_variance * std::exp(kPilotStandardErrors * error);
  if (pair[0].relative_variance > 0.0) m.relative_variance *= pair[1].relative_variance / pair[0].relative_variance;
  m.efficiency = 1.0 / (std::max(m.relative_variance, kNoiseFloor) * m.cost);
  return m;
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
/// `noise` is the grid's strategies', pixel by pixel; kPilotReuse's measure, where the pilot
/// weighed it, follows theirs, known through kPilotReused's: its error against a grid strategy
/// adds that of its ratio to kPilotReused's on the blocks, `reuse_error`.
void measure_errors(std::vector<PilotMeasure>& pilot, const std::vector<std::vector<double>>& noise, std::size_t best,
                    double reuse_error) {
  const std::size_t grid = noise.size();
  for (std::size_t s = 0; s < pilot.size(); ++s) {
    if (s < grid && best < grid) {
      pilot[s].relative_error = log_ratio_error(noise[s], noise[best]);
    } else if (s != best) {
      const std::size_t other = s < grid ? s : best;
      pilot[s].relative_error = std::hypot(log_ratio_error(noise[other], noise[kPilotReused]), reuse_error);
    } else {
      pilot[s].relative_error = 0.0;
    }
  }
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

/// E[(e^d - 1)^+] for d ~ N(m, sigma^2): by how much of the leader's efficiency another is
/// ahead of it, where it is, when d is the log of the ratio of their efficiencies.
double expected_excess(double m, double sigma) {
  if (!(sigma > 0.0)) return std::max(0.0, std::expm1(m));
  const auto normal_cdf = [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); };
  return std::exp(m + 0.5 * sigma * sigma) * normal_cdf(m / sigma + sigma) - normal_cdf(m / sigma);
}

std::string pilot_reason(const std::vector<PilotMeasure>& pilot, std::size_t best, std::size_t chosen,
                         const PilotPixels& grid, const PilotPixels& blocks, unsigned passes, const char* stop) {
  char text[768];
  const PilotMeasure& b = pilot[best];
  int n = std::snprintf(text, sizeof text, "a pilot of %u passes%s on %zu pixels", passes, stop, grid.size());
  if (blocks.size() > 0 && n > 0 && std::size_t(n) < sizeof text)
    n += std::snprintf(text + n, sizeof text - n, " (%s against %s on %zu more, in blocks)", kPilotReuse,
                       kPilotStrategies[kPilotReused], blocks.size());
  if (n > 0 && std::size_t(n) < sizeof text)
    n += std::snprintf(text + n, sizeof text - n, ": %s is the most efficient (relative variance %.3g a pass, cost %.3g rays a pass)",
                       b.strategy.c_str(), b.relative_variance, b.cost);
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
  measure_errors(pilot, noise, best, 0.0);
  return decided(pilot, best);
}

double pilot_round_gain(std::vector<PilotMeasure> pilot, const std::vector<std::vector<double>>& noise,
                        unsigned passes) {
  if (pilot.empty()) return 0.0;
  const std::size_t best = leader(pilot);
  measure_errors(pilot, noise, best, 0.0);
  const double kept = double(passes) / double(passes + kPilotRoundPasses);  // of the error's square
  double gain = 0.0;
  for (std::size_t s = 0; s < pilot.size(); ++s) {
    if (s == best) continue;
    const double error = pilot[s].relative_error, after = error * error * kept;
    gain += expected_excess(std::log(pilot[s].efficiency / pilot[best].efficiency) + 0.5 * after,
                            std::sqrt(error * error - after));
  }
  return gain;
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
  // restir against ris on blocks, where the budget pays for enough of them; without scattering,
  // restir's reservoirs light nothing: it is ris.
  const unsigned side = std::min({kPilotBlockSide, settings.width, settings.height});
  const double affordable = kPilotBlockShare * budget / kMinPilotPasses / (2.0 * side * side);
  const unsigned block_count = unsigned(std::clamp(affordable, 0.0, double(kPilotBlocks)));
  const std::size_t block_runs = settings.max_depth > 0 && block_count >= kMinPilotBlocks ? 2 : 0;
  PilotPixels blocks;  // placed after the grid's first round
  const double block_paths = double(block_runs * block_count * side * side);
  const PilotPixels grid =
      pilot_grid(settings.width, settings.height,
                 std::clamp((budget / kMinPilotPasses - block_paths) / double(strategies), kMinPilotPixels, kPilotPixels));
  const double pass_paths = double(strategies * grid.size()) + block_paths;
  const auto within_budget = [&](unsigned passes) { return passes * pass_paths <= budget; };
  // What another round would take of the render: its paths' share of the render's, and, to a
  // deadline, its time's share of the time left, a round taking as long as the last.
  const auto round_share = [&](std::chrono::steady_clock::time_point round_start) {
    const double paths = kPilotRoundPasses * pass_paths / (double(settings.spp) * double(pixels));
    if (!settings.deadline) return paths;
    const auto now = std::chrono::steady_clock::now();
    if (now >= *settings.deadline) return std::numeric_limits<double>::infinity();
    return std::max(paths, std::chrono::duration<double>(now - round_start) / (*settings.deadline - now));
  };
  // A strategy's pilot over `on`, with point lights in proportion to its pixels: a connection
  // picks one light of the set, so the noise per path is the same (renderer.h, kAutoLightsPerQuery).
  const auto make_run = [&](PilotRun& run, const char* kind, const PilotPixels& on, double light_sample_cost) {
    StrategyOptions o = options;
    o.kind = kind;
    o.lights = std::max(1.0, std::round(options.lights * double(on.size()) / double(pixels)));
    run.pixels = &on;
    run.lights = o.lights;
    run.light_sample_cost = light_sample_cost;
    run.strategy = make_light_strategy(emitters, o);
    run.tracer.emplace(scene, geometry, emitters, *run.strategy, settings.max_depth);
    if (const ReuseOptions* reuse = reuse_of(*run.strategy))
      run.reuse.emplace(*run.tracer, emitters, *run.strategy, *reuse, on.width, on.height);
    run.work.resize(on.size());
    run.luminance.resize(on.size() * kMaxPilotPasses);
    run.lit.resize(on.size() * kMaxPilotPasses);
  };
  std::vector<PilotRun> runs(strategies), paired;
  for (std::size_t s = 0; s < strategies; ++s) {
    make_run(runs[s], kPilotStrategies[s], grid, kPilotLightSampleCost[s]);
    choice.pilot.push_back({kPilotStrategies[s]});
  }
  std::vector<PilotMeasure> pair;
  std::size_t best = 0;
  unsigned passes = 0;
  bool knew = false;     // whether it stopped because no other strategy can be far ahead
  bool repaid = false;   // or because another round would cost more than it could win back
  while (passes < kMaxPilotPasses) {
    const auto round_start = std::chrono::steady_clock::now();
    for (PilotRun& run : runs) run_passes(run, camera, settings.width, passes, passes + kPilotRoundPasses);
    if (block_runs > 0 && paired.empty()) {
      blocks = pilot_blocks(settings.width, settings.height, side,
                            block_centres(runs, runs[kPilotReused], passes + kPilotRoundPasses, block_count));
      paired.resize(block_runs);
      make_run(paired[0], kPilotStrategies[kPilotReused], blocks, kPilotLightSampleCost[kPilotReused]);
      make_run(paired[1], kPilotReuse, blocks, kPilotLightSampleCost[kPilotReused]);
      pair = {{kPilotStrategies[kPilotReused]}, {kPilotReuse}};
    }
    for (PilotRun& run : paired) run_passes(run, camera, settings.width, passes, passes + kPilotRoundPasses);
    passes += kPilotRoundPasses;
    if (passes < kMinPilotPasses) continue;
    choice.pilot.resize(strategies);
    const std::vector<std::vector<double>> noise = measure_pilot(runs, passes, options.lights, pixels, choice.pilot);
    double reuse_error = 0.0;
    if (block_runs > 0) {
      const std::vector<std::vector<double>> pair_noise = measure_pilot(paired, passes, options.lights, pixels, pair);
      // Over the blocks, not their pixels: a block's pixels share its surface and lights.
      reuse_error = log_ratio_error(block_sums(pair_noise[1], blocks), block_sums(pair_noise[0], blocks));
      choice.pilot.push_back(reuse_measure(choice.pilot[kPilotReused], pair, reuse_error));
    }
    best = leader(choice.pilot);
    measure_errors(choice.pilot, noise, best, reuse_error);
    // Whether to go on (pilot_decided) counts restir's blocks' error once, as its measure
    // already does (reuse_measure), not again on top of it: restir then renders where the pilot
    // knows it leads, and holds the pilot no longer than ris would.
    knew = pilot_decided(choice.pilot, noise);
    repaid = !knew && pilot_round_gain(choice.pilot, noise, passes) <= round_share(round_start);
    if (knew || repaid || !within_budget(passes + kPilotRoundPasses)) break;
  }
  const std::size_t rendering = cheapest_close_to(choice.pilot, best);
  choice.pilot_passes = passes;
  choice.pilot_pixels = grid.size();
  choice.pilot_block_pixels = blocks.size();
  choice.most_efficient = choice.pilot[best].strategy;
  choice.options.kind = choice.pilot[rendering].strategy;
  const char* stop = knew     ? ""
                     : repaid ? " (another would cost more of the render than it could win back)"
                     : passes == kMaxPilotPasses ? " (its most)"
                                                 : " (its share of the render)";
  choice.reason = pilot_reason(choice.pilot, best, rendering, grid, blocks, passes, stop);
  chosen.strategy = make_light_strategy(emitters, choice.options);  // with the render's lights
  chosen.pilot_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return chosen;
}

}  // namespace tracer
