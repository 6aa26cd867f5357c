#pragma once
// Progressive rendering: pass after pass, one path per pixel each, averaged. With `trs` every
// pass draws a fresh set of point lights first. A frame is an animation frame: a still is frame
// 0.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tracer/emitters.h"
#include "tracer/light_strategy.h"
#include "tracer/scene.h"

namespace tracer {

/// Seconds into the scene's animation of frame `frame`, at `fps` frames per second.
inline double animation_seconds(std::int64_t frame, double fps) { return double(frame) / fps; }

struct RenderSettings {
  unsigned width = 640;
  unsigned height = 360;
  unsigned spp = 16;        ///< passes (with a deadline: the most passes)
  /// No pass starts at or after this instant; the first always runs. `auto`'s pilot weighs a
  /// round against the time left to it.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  unsigned max_depth = 4;   ///< see PathTracer
  /// Animation frame f renders with its own random streams, from seed ^ mix64(f): frame 0's are
  /// a still image's.
  std::uint64_t seed = 0;
  /// Animation frames per second: frame f is animation_seconds(f, fps) into the scene's animation.
  double fps = 24.0;
  unsigned threads = 0;     ///< paths and CPU light sampler; 0: every hardware thread
  StrategyOptions strategy;
  /// The light sampler's backend and device (its CPU threads are `threads`).
  lightsampler::SamplerOptions sampler;
};

/// Point lights per pass for `trs` when none is given: a quarter of the pass's next-event
/// queries (pixels times max_depth), at least one. A connection picks one light of the set, so
/// the per-pixel noise is the same with any set size; what the size buys is independence
/// between pixels, whose shared error has about 1/N of one connection's variance. At a quarter
/// of the queries, measured with trs-study (docs/noise.md), it is gone at the scale of 32 x 32
/// pixel blocks, and a larger set only costs time.
inline constexpr double kAutoLightsPerQuery = 0.25;
double auto_lights(unsigned width, unsigned height, unsigned max_depth);

/// The set-up by part, milliseconds: the scene's loading, then what RenderResult::setup_seconds
/// is made of.
struct SetupTimes {
  double loading_ms = 0.0;          ///< reading the scene (Scene::load_seconds), its texture decoding excluded
  double texture_decoding_ms = 0.0; ///< decoding its texture images
  double bvh_ms = 0.0;              ///< the scene's ray-tracing structure
  double emission_ms = 0.0;         ///< the emission maps and the lights' mesh (EmittersSetup)
  double light_sampler_ms = 0.0;    ///< the light sampler's construction and first count
  double subdivision_ms = 0.0;      ///< the light sampler's subdivision
  double light_structure_ms = 0.0;  ///< the strategy's own structure (the tree, alias tables)
  double pilot_ms = 0.0;            ///< `auto`: its pilot passes, and the texel gain's frame
  std::uint64_t sampler_parts = 0;  ///< triangles the light sampler samples
};

struct RenderResult {
  unsigned width = 0;
  unsigned height = 0;
  unsigned passes = 0;                ///< passes averaged (samples per pixel)
  std::vector<float> rgb;             ///< mean radiance, width * height * 3, row 0 at the top
  /// Per-pixel variance of one path's luminance over the passes (unbiased; zero below two
  /// passes): the noise of one sample per pixel, comparable between strategies.
  std::vector<float> luminance_variance;
  /// Per pixel, the fraction of its camera samples whose first hit is an emitter: where the
  /// noise comes from the pixel footprint over an emitter, whatever the light strategy.
  std::vector<float> emitter_fraction;
  std::vector<LightPass> light_passes;  ///< per pass
  /// restir: the reuse's time per pass, milliseconds (its reservoirs gathered, temporal and
  /// spatial); empty for the other strategies.
  std::vector<double> reuse_ms;
  /// restir: the candidates its reservoirs weighed and its evaluations of the target at a surface,
  /// over all passes (the light samples its reuse adds to light_samples' and the rays' work).
  std::uint64_t reuse_candidates = 0, reuse_targets = 0;
  StrategySetup light_structure;      ///< what the strategy built over the lights (zeros: nothing)
  double setup_seconds = 0.0;         ///< scene acceleration structure, emitters, strategy
  SetupTimes setup;                   ///< setup_seconds by part
  double first_pass_seconds = 0.0;    ///< the first pass's wall time (its lights drawn, its paths traced)
  double render_seconds = 0.0;        ///< the passes, light sampling included
  std::uint64_t paths = 0;
  std::uint64_t rays = 0;             ///< closest-hit and shadow rays traced
  /// Light samples weighed for next-event estimation: queries times the strategy's candidates
  /// (restir's reuse not counted).
  std::uint64_t light_samples = 0;
  std::uint64_t invalid_paths = 0;    ///< paths with a NaN or infinite estimate, counted as black
  bool interrupted = false;           ///< stopped early by the cancel flag (not by the deadline)
  std::string strategy;               ///< the strategy that rendered
  StrategyChoice strategy_choice;     ///< its options, and for `auto` why it was chosen
  std::uint32_t punctual_lights = 0;  ///< the scene's punctual lights, sampled beside its emission
  std::string light_device;           ///< the light sampler's backend and device, if any
};

class Renderer {
 public:
  /// Builds the ray-tracing structure, the emitters and the strategy, the emission as it is at
  /// animation frame `frame`. Throws std::invalid_argument on a scene that cannot be rendered
  /// with these settings (a still whose lights emit nothing, say).
  Renderer(const Scene& scene, const RenderSettings& settings, std::int64_t frame = 0);
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  ~Renderer();

  /// Moves to animation frame `frame`: the emission that changes is replaced, and the light
  /// strategy updates what depends on it. The next render() or render_more() renders that frame
  /// from its first sample.
  EmissionUpdate set_frame(std::int64_t frame);
  /// The instant at or after which the next render() starts no pass (RenderSettings::deadline).
  void set_deadline(std::optional<std::chrono::steady_clock::time_point> deadline);

  /// Renders settings.spp passes, or fewer by the deadline. `progress(done, total)` after each
  /// pass. When `cancel` becomes true, the pass under way is dropped and the passes done so
  /// far are returned.
  RenderResult render(const std::function<void(unsigned, unsigned)>& progress,
                      const std::atomic<bool>& cancel);
  /// Renders `count` passes more (fewer by the deadline or `cancel`, as render() does) after
  /// those that render() or render_more() rendered of this animation frame, each with the random
  /// streams render() gives it: the result averages them all, and render_more(1) n times from
  /// the start equals render() with n spp. `progress` counts this call's passes.
  RenderResult render_more(unsigned count, const std::function<void(unsigned, unsigned)>& progress,
                           const std::atomic<bool>& cancel);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tracer
