#include "tracer/renderer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "luminance.h"
#include "tracer/camera.h"
#include "tracer/emitters.h"
#include "tracer/geometry.h"
#include "tracer/path_tracer.h"
#include "tracer/strategy_registry.h"
#include "pixel_ray.h"
#include "reuse.h"
#include "strategy_choice.h"

namespace tracer {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Camera scene_camera(const Scene& scene) {
  if (scene.camera) return *scene.camera;
  glm::vec3 lower(INFINITY), upper(-INFINITY);
  for (const glm::vec3& p : scene.mesh.positions) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  return framing_camera(lower, upper);
}


/// Sums over passes per pixel, in double: thousands of passes of float noise.
struct Accumulator {
  std::vector<double> rgb;
  std::vector<double> luminance_squared;
  std::vector<std::uint32_t> emitter_hits;

  explicit Accumulator(std::size_t pixels)
      : rgb(3 * pixels, 0.0), luminance_squared(pixels, 0.0), emitter_hits(pixels, 0) {}

  void add(const std::vector<PathEstimate>& pass) {
    for (std::size_t i = 0; i < pass.size(); ++i) {
      for (int c = 0; c < 3; ++c) rgb[3 * i + c] += pass[i].radiance[c];
      const double y = luminance(pass[i].radiance);
      luminance_squared[i] += y * y;
      emitter_hits[i] += pass[i].sees_emitter ? 1 : 0;
    }
  }

  void finish(unsigned passes, RenderResult& result) const {
    const std::size_t pixels = luminance_squared.size();
    result.rgb.assign(3 * pixels, 0.0f);
    result.luminance_variance.assign(pixels, 0.0f);
    result.emitter_fraction.assign(pixels, 0.0f);
    if (passes == 0) return;
    for (std::size_t i = 0; i < 3 * pixels; ++i) result.rgb[i] = float(rgb[i] / passes);
    for (std::size_t i = 0; i < pixels; ++i) result.emitter_fraction[i] = float(double(emitter_hits[i]) / passes);
    if (passes < 2) return;
    for (std::size_t i = 0; i < pixels; ++i) {
      const double mean = trs::luminance(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]) / passes;
      const double variance = (luminance_squared[i] / passes - mean * mean) * passes / (passes - 1);
      result.luminance_variance[i] = float(std::max(variance, 0.0));
    }
  }
};

lightsampler::SamplerOptions sampler_options(const RenderSettings& settings) {
  lightsampler::SamplerOptions options = settings.sampler;
  options.cpu.threads = settings.threads;
  // The subdivision speeds up drawing lights; the other strategies only read integrals and texels.
  // `auto` measures on the sampler `ris` draws from, where the texture decides, and renders with
  // it: built once, subdivided, rather than once for the measure and again for `ris`.
  if (!draws_point_lights(settings.strategy) && settings.strategy.kind != kAutoStrategy)
    options.refinement = {};
  // The cost model splits for the lights a pass draws.
  if (options.refinement.cost_model) options.refinement.frame_samples = settings.strategy.lights;
  return options;
}

/// The lights of a still must emit something; an animation's may be dark in some frames.
Emitters& lit(Emitters& emitters, const Scene& scene) {
  if (emitters.count() > 0 && !(emitters.total_density() > 0.0) && !scene.animated())
    throw std::invalid_argument("the lights emit nothing: no emissive texel has any luminance");
  return emitters;
}

/// Calls `f(x, y)` for every pixel, in 8 x 8 tiles over the threads; stops early on `cancel`.
template <class F>
void for_each_pixel(const RenderSettings& settings, const std::atomic<bool>& cancel, F&& f) {
  tbb::parallel_for(tbb::blocked_range2d<unsigned>(0, settings.height, 8, 0, settings.width, 8),
                    [&](const tbb::blocked_range2d<unsigned>& tile) {
                      if (cancel) return;
                      for (unsigned y = tile.rows().begin(); y != tile.rows().end(); ++y)
                        for (unsigned x = tile.cols().begin(); x != tile.cols().end(); ++x) f(x, y);
                    });
}

}  // namespace

struct Renderer::State {
  const Scene& scene;
  RenderSettings settings;
  std::int64_t frame;
  double setup_seconds = 0.0;
  // The instants between the parts of the set-up, taken as the members are built, in order.
  Clock::time_point start = Clock::now();
  Geometry geometry;
  Clock::time_point geometry_built = Clock::now();
  Emitters emitters;
  Clock::time_point emitters_built = Clock::now();
  PinholeCamera camera;
  /// The strategy; `auto` chooses again at each animation frame whose emission changed, so that
  /// every frame renders as its still.
  ChosenStrategy chosen;
  double setup_pilot_ms = chosen.pilot_ms;  ///< the set-up's pilot (`auto`)
  Clock::time_point strategy_built = Clock::now();
  std::optional<PathTracer> tracer;
  /// restir's reservoirs; none for the other strategies, nor where paths do not scatter.
  std::optional<Reuse> reuse;
  double first_pass_seconds = 0.0;  ///< of the passes of this animation frame
  /// The passes rendered so far of this animation frame; render() starts it again.
  struct Sums {
    Accumulator pixels;
    std::vector<LightPass> light_passes;
    std::vector<double> reuse_ms;
    ReuseWork reuse_work;
    unsigned passes = 0;
    double seconds = 0.0;
    std::uint64_t rays = 0;
    std::uint64_t light_queries = 0;
    std::uint64_t invalid_paths = 0;
  };
  std::optional<Sums> sums;

  State(const Scene& s, const RenderSettings& r, std::int64_t f)
      : scene(s),
        settings(r),
        frame(f),
        geometry(s),
        emitters(s, sampler_options(r), f, animation_seconds(f, r.fps)),
        camera(scene_camera(s), r.width, r.height),
        chosen(choose_strategy(s, geometry, lit(emitters, s), camera, r)) {
    make_tracer();
  }

  /// The path tracer and reuse of the chosen strategy (none before: a reuse refers to both).
  void make_tracer() {
    tracer.emplace(scene, geometry, emitters, *chosen.strategy, settings.max_depth);
    const ReuseOptions* options = reuse_of(*chosen.strategy);
    if (options && settings.max_depth > 0)  // without scattering nothing is lit by a light sample
      reuse.emplace(*tracer, emitters, *chosen.strategy, *options, settings.width, settings.height);
  }

  LightStrategy& strategy() const { return *chosen.strategy; }
};

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, std::int64_t frame) {
  if (settings.width == 0 || settings.height == 0)
    throw std::invalid_argument("the image needs a width and a height of at least 1");
  if (std::uint64_t(settings.width) * settings.height >= (1ull << 32))
    throw std::invalid_argument("the image has 2^32 pixels or more");
  if (!(settings.fps > 0.0) || !std::isfinite(settings.fps))
    throw std::invalid_argument("the frame rate must be positive and finite");
  const auto start = Clock::now();
  state_ = std::make_unique<State>(scene, settings, frame);
  state_->setup_seconds = seconds_since(start);
}

void Renderer::set_deadline(std::optional<Clock::time_point> deadline) { state_->settings.deadline = deadline; }

EmissionUpdate Renderer::set_frame(std::int64_t frame) {
  State& s = *state_;
  s.frame = frame;
  s.sums.reset();
  EmissionUpdate update = s.emitters.set_frame(frame, animation_seconds(frame, s.settings.fps));
  if (update.changed()) {
    const auto start = Clock::now();
    if (s.settings.strategy.kind == kAutoStrategy) {
      s.reuse.reset();  // it refers to the tracer and the strategy, both remade
      s.tracer.reset();
      s.chosen = choose_strategy(s.scene, s.geometry, s.emitters, s.camera, s.settings);
      s.make_tracer();
    } else {
      s.strategy().emission_changed();
    }
    update.strategy_ms = 1000.0 * seconds_since(start);
  }
  return update;
}

Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

RenderResult Renderer::render(const std::function<void(unsigned, unsigned)>& progress,
                              const std::atomic<bool>& cancel) {
  state_->sums.reset();
  return render_more(state_->settings.spp, progress, cancel);
}

RenderResult Renderer::render_more(unsigned count, const std::function<void(unsigned, unsigned)>& progress,
                                   const std::atomic<bool>& cancel) {
  State& s = *state_;
  const RenderSettings& settings = s.settings;
  std::optional<tbb::global_control> limit;
  if (settings.threads > 0)
    limit.emplace(tbb::global_control::max_allowed_parallelism, settings.threads);
  const std::size_t pixels = std::size_t(settings.width) * settings.height;
  const PathTracer& tracer = *s.tracer;
  const std::uint64_t frame_seed = settings.seed ^ lightsampler::mix64(std::uint64_t(s.frame));
  const lightsampler::PhiloxKey key = path_key(frame_seed);
  const lightsampler::PhiloxKey gather_key = path_key(frame_seed ^ kGatherStream);
  const lightsampler::PhiloxKey spatial_key = path_key(frame_seed ^ kSpatialStream);
  if (!s.sums) {
    s.sums.emplace(State::Sums{Accumulator(pixels), {}, {}, {}, 0, 0.0, 0, 0, 0});
    if (s.reuse) s.reuse->reset();
  }
  State::Sums& sums = *s.sums;

  std::vector<PathEstimate> pass(pixels);
  tbb::combinable<std::uint64_t> rays, queries, invalid;
  tbb::combinable<ReuseWork> reuse_work;
  const auto start = Clock::now();
  const unsigned first = sums.passes;
  const unsigned end = first + std::min(count, std::numeric_limits<unsigned>::max() - first);
  bool cancelled = false;
  for (unsigned f = first; f < end; ++f) {
    if (cancel) {
      cancelled = true;
      break;
    }
    // The light sets of animation frames apart as their paths are: frame 0's are a still's.
    const auto pass_start = Clock::now();
    s.strategy().begin_pass(pass_seed(settings.seed, std::uint64_t(s.frame) << 32 | f));
    if (s.reuse) {
      const auto reuse_start = Clock::now();
      s.reuse->begin_pass();
      for_each_pixel(settings, cancel, [&](unsigned x, unsigned y) {
        const std::uint32_t pixel = y * settings.width + x;
        PathRandom path(key, pixel, f), random(gather_key, pixel, f);
        s.reuse->gather(pixel, pixel_ray(s.camera, x, y, path), random, rays.local(), reuse_work.local());
      });
      for_each_pixel(settings, cancel, [&](unsigned x, unsigned y) {
        const std::uint32_t pixel = y * settings.width + x;
        PathRandom random(spatial_key, pixel, f);
        s.reuse->spatial(pixel, random, reuse_work.local());
      });
      sums.reuse_ms.push_back(1000.0 * seconds_since(reuse_start));
    }
    for_each_pixel(settings, cancel, [&](unsigned x, unsigned y) {
      const std::uint32_t pixel = y * settings.width + x;
      PathRandom random(key, pixel, f);
      const Ray ray = pixel_ray(s.camera, x, y, random);
      std::optional<PathTracer::FirstSurface> first;
      if (s.reuse) first = s.reuse->first_surface(pixel);
      PathEstimate e = tracer.radiance(ray, random, rays.local(), first ? &*first : nullptr);
      queries.local() += e.light_queries;
      const glm::vec3& l = e.radiance;
      if (!std::isfinite(l.r + l.g + l.b)) {
        ++invalid.local();
        e.radiance = glm::vec3(0.0f);
      }
      pass[pixel] = e;
    });
    if (cancel) {  // a partial pass would bias the average
      cancelled = true;
      break;
    }
    s.geometry.throw_if_failed();
    sums.pixels.add(pass);
    sums.light_passes.push_back(s.strategy().last_pass());
    sums.passes = f + 1;
    if (f == 0) s.first_pass_seconds = seconds_since(pass_start);
    if (progress) progress(f + 1 - first, end - first);
    if (settings.deadline && Clock::now() >= *settings.deadline) break;
  }
  sums.seconds += seconds_since(start);
  sums.rays += rays.combine(std::plus<>());
  sums.light_queries += queries.combine(std::plus<>());
  sums.invalid_paths += invalid.combine(std::plus<>());
  reuse_work.combine_each([&](const ReuseWork& w) { sums.reuse_work += w; });

  RenderResult result;
  result.width = settings.width;
  result.height = settings.height;
  result.setup_seconds = s.setup_seconds;
  const EmittersSetup& lights = s.emitters.setup();
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  result.setup = {1000.0 * (s.scene.load_seconds - s.scene.texture_decode_seconds), 1000.0 * s.scene.texture_decode_seconds,
                  ms(s.start, s.geometry_built), lights.emission_ms, lights.sampler_ms, lights.subdivision_ms,
                  ms(s.emitters_built, s.strategy_built) - s.setup_pilot_ms, s.setup_pilot_ms, lights.sampler_parts};
  result.first_pass_seconds = s.first_pass_seconds;
  result.strategy = s.strategy().name();
  result.strategy_choice = s.chosen.choice;
  result.punctual_lights = s.emitters.punctual().count();
  result.light_device = s.strategy().device();
  result.light_structure = s.strategy().setup();
  result.passes = sums.passes;
  result.light_passes = sums.light_passes;
  result.reuse_ms = sums.reuse_ms;
  result.reuse_candidates = sums.reuse_work.candidates;
  result.reuse_targets = sums.reuse_work.targets;
  result.render_seconds = sums.seconds;
  result.interrupted = cancelled;
  result.paths = std::uint64_t(result.passes) * pixels;
  result.rays = sums.rays;
  result.light_samples = sums.light_queries * s.strategy().candidates();
  result.invalid_paths = sums.invalid_paths;
  sums.pixels.finish(result.passes, result);
  return result;
}

double auto_lights(unsigned width, unsigned height, unsigned max_depth) {
  const double queries = double(width) * double(height) * double(std::max(max_depth, 1u));
  return std::max(1.0, std::round(kAutoLightsPerQuery * queries));
}

}  // namespace tracer
