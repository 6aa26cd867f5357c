#pragma once
// How next-event estimation picks a point on the lights. One interface; each strategy is one
// small file in src/strategies/.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <lightsampler/random.h>
#include <lightsampler/sampler.h>

#include "tracer/emitters.h"

namespace tracer {

/// emitters.light(light).point(b1, b2, pdf, mis_pdf): the point (b1, b2) of emissive triangle
/// `light` with the densities given.
LightPoint light_point(const Emitters& emitters, std::uint32_t light, float b1, float b2,
                       float pdf, float mis_pdf);

/// emitters.light(point.light).sample_li(point, at): `point` seen from `at`.
std::optional<LightLiSample> seen_from(const Emitters& emitters, const LightPoint& point, const ShadingPoint& at);

/// What a strategy draws one point from: eight independent uniform 32-bit words (two blocks of
/// the path's Philox stream).
using LightRandom = std::array<std::uint32_t, 8>;

/// Words k and k + 1 of `random` as one uniform 64-bit word.
inline std::uint64_t word64(const LightRandom& random, int k) {
  return std::uint64_t(random[k]) | std::uint64_t(random[k + 1]) << 32;
}

/// A uniform double in [0, 1) from 53 bits of words k and k + 1: a walk down a deep tree reads a
/// few bits of it at every level.
inline double uniform53(const LightRandom& random, int k) { return double(word64(random, k) >> 11) * 0x1p-53; }

/// What a strategy's light sampler did for one pass of paths (one path per pixel).
struct LightPass {
  double sampler_ms = 0.0;     ///< light-sampler time, milliseconds
  std::uint64_t lights = 0;    ///< point lights drawn
  std::uint64_t candidates = 0;  ///< points the rejection loops tried
  std::uint64_t exhausted = 0; ///< lights that reached the sampler's rejection limit (biased)
  std::vector<lightsampler::PassTime> passes;  ///< the sampler's time per pass
  double records_ms = 0.0;     ///< writing the lights' records, milliseconds
};

/// What a strategy built before the first pass, for reports: zeros for strategies without a
/// structure of their own.
struct StrategySetup {
  double build_ms = 0;     ///< time to build it, milliseconds
  std::size_t bytes = 0;   ///< memory it holds
};

/// The seed of pass `pass`'s lights in a render of seed `seed`: `trs` draws its point lights with
/// it. The renderer numbers a pass by its animation frame (high 32 bits) and its index within it.
inline std::uint64_t pass_seed(std::uint64_t seed, std::uint64_t pass) {
  return lightsampler::mix64(seed ^ lightsampler::mix64(pass));
}

class LightStrategy {
 public:
  virtual ~LightStrategy() = default;

  virtual std::string name() const = 0;
  /// Called before each pass of paths with the seed of its lights (pass_seed()).
  virtual void begin_pass(std::uint64_t seed) { (void)seed; }
  /// The emitters' emission changed (Emitters::set_frame): whatever the strategy built from it
  /// is built again, or refitted.
  virtual void emission_changed() {}
  /// A light sample seen from `at`; none when the lights have nothing to offer it this pass.
  virtual std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const = 0;
  /// Starts bringing what sample() will read for these words into the cache, so that a shading
  /// point's candidates wait for memory together rather than one after another.
  virtual void prefetch(const LightRandom& random) const { (void)random; }
  /// Area density with which sample(., from) picks a point of a light; what a BSDF-sampled hit
  /// on the light, seen from `from`, weighs against.
  virtual float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const = 0;

  /// Light samples each next-event connection is resampled from (PathTracer::light_sample):
  /// `ris`'s candidates, one for the others.
  virtual unsigned candidates() const { return 1; }

  /// What the light sampler did in the last pass (zeros for strategies without one).
  virtual LightPass last_pass() const { return {}; }
  /// The sampler's backend and device, for reports; empty for strategies without one.
  virtual std::string device() const { return {}; }
  /// The structure the strategy built over the lights (the light tree's).
  virtual StrategySetup setup() const { return {}; }
};

/// ris: candidates per shading point when none is given (docs/noise.md, "Resampled lights").
inline constexpr unsigned kDefaultCandidates = 4;

/// tree: how a node's importance for a shading point is estimated (tree_importance.h).
enum class TreeImportance { pbrt, cycles };
/// tree: the power each light is weighed with.
enum class TreePower {
  exact,       ///< its emitted power: the integral of its texels' luminance over it
  image_mean,  ///< its area times the mean of its whole emission map, as pbrt-v4 takes it
};

struct TreeOptions {
  TreeImportance importance = TreeImportance::pbrt;
  TreePower power = TreePower::exact;
};

struct StrategyOptions {
  /// A registered strategy's name (strategy_registry.h), or `auto`: the most efficient of
  /// kPilotStrategies on the scene, by a pilot (Renderer; docs/noise.md).
  std::string kind = "auto";
  double lights = 1e6;          ///< trs (and ris over it): expected point lights per pass (N_target)
  unsigned candidates = kDefaultCandidates;  ///< ris: points resampled per shading point
  std::string candidates_from = "trs";  ///< ris: the strategy its candidates come from
  TreeOptions tree;  ///< tree (and ris over it)
  /// A plugin's own options, by name (trs-render --strategy-option NAME=VALUE); the built-in
  /// strategies read none.
  std::map<std::string, std::string> parameters;
};

/// The strategy that draws the points: the one named, or for `ris` and `restir` the one their
/// candidates come from.
const std::string& source_kind(const StrategyOptions& options);

/// Whether the strategy picks lights with the light tree (and reads StrategyOptions::tree).
bool picks_by_tree(const StrategyOptions& options);

/// Whether the strategy draws a set of point lights every pass (`auto` only once it chose one).
bool draws_point_lights(const StrategyOptions& options);

/// Whether `ris` can draw its candidates from the strategy `name`: a registered one that does not
/// resample itself.
bool resamplable(const std::string& name);

/// One strategy as `auto`'s pilot measured it: a few passes over a grid of the image's pixels,
/// with seeds of the pilot's own.
struct PilotMeasure {
  std::string strategy;
  /// The noise of one pass: per pixel, the variance of a path's luminance (the emission the
  /// camera ray met left out, the same for every strategy) over the square of the median of
  /// every strategy's pilot paths there plus relMSE's guard (scene_io/relmse.h), averaged over
  /// the pilot's pixels. One pass's expected relMSE, less what no strategy changes.
  double relative_variance = 0.0;
  /// The standard error, over the pilot's pixels, of the log of this strategy's relative_variance
  /// over the most efficient one's (0 for that one): how well the pilot knew their ratio.
  double relative_error = 0.0;
  /// A pass's work over the whole image, in rays: rays traced, light samples weighed and the
  /// light sampler's tries, each at its unit cost (a light sample's by strategy;
  /// strategy_choice.cpp).
  double cost = 0.0;
  double efficiency = 0.0;  ///< 1 / (relative_variance * cost)
  double rays_per_path = 0.0;
  double light_samples_per_path = 0.0;  ///< next-event queries times the strategy's candidates, and restir's reuse's
  double targets_per_path = 0.0;  ///< restir: its reuse's evaluations of the target at a surface
  double sampler_tries_per_pass = 0.0;  ///< candidates the light sampler's rejection loops tried
};

/// The strategies `auto`'s pilot weighs over a grid of pixels: between them the most efficient at
/// equal time on every scene measured but the damaged helmet, where `restir` is (docs/noise.md,
/// "The default chooses by a pilot"). restir's reuse draws on neighbouring pixels, which a grid
/// lacks: the pilot weighs it against `ris` on blocks of neighbouring pixels (kPilotReuse).
inline constexpr const char* kPilotStrategies[] = {"power", "trs", "ris"};
/// The strategy weighed on blocks, against the one of kPilotStrategies it reuses the samples of.
inline constexpr const char* kPilotReuse = "restir";
inline constexpr std::size_t kPilotReused = 2;  // ris

/// The pilot's passes of each strategy: rounds of kPilotRoundPasses, at least kMinPilotPasses and
/// at most kMaxPilotPasses. It stops once no other strategy can be more than kPilotIndifference
/// more efficient than the most efficient, by kPilotStandardErrors standard errors of the ratio
/// of their noises: where the strategies are far apart, or known to be close enough that either
/// loses little, more passes would not change what renders. It stops as well once another round
/// would take a larger share of the render than it is expected to win back (pilot_round_gain).
inline constexpr unsigned kPilotRoundPasses = 2, kMinPilotPasses = 4, kMaxPilotPasses = 8;
inline constexpr double kPilotIndifference = 0.1, kPilotStandardErrors = 2.0;

/// The most of the render's paths (its passes over the whole image) the pilot spends choosing:
/// its grid is smaller for a short render (down to kMinPilotPixels, strategy_choice.cpp), and it
/// takes a round beyond kMinPilotPasses only within this share. What a better choice saves is a
/// share of the render, so a preview of a few passes cannot repay a pilot that a final render
/// can; a render to a deadline alone is not bounded by it.
inline constexpr double kPilotShare = 0.1;

/// The cheapest strategy within this of the most efficient renders. The pilot's noise is what it
/// saw, and what it misses most is the rare bright paths that no light strategy draws (light
/// reached through glass or off a mirror, fireflies): the same for every strategy, lowered only
/// by more passes, so where the pilot finds strategies close the cheaper one is the better bet.
/// Chosen on the 16 scenes of docs/noise.md ("The default chooses by a pilot"), with each
/// strategy's light samples at their own cost.
inline constexpr double kCheaperMargin = 0.10;

/// Which of the pilot's measures renders: the cheapest of those whose efficiency is within
/// kCheaperMargin of the most efficient (the first most efficient, in kPilotStrategies' order,
/// on a tie).
std::size_t strategy_to_render(const std::vector<PilotMeasure>& pilot);

/// Whether the pilot may stop: no other strategy can be more than kPilotIndifference more
/// efficient than the most efficient, by kPilotStandardErrors standard errors of the ratio of
/// their noises. `noise` holds each strategy's noise pixel by pixel, the same pixels for all
/// (paired: the pixel-to-pixel spread the strategies share cancels in the ratio): those of
/// kPilotStrategies. kPilotReuse's measure, where `pilot` has it, is known here as well as
/// kPilotReused's: the error of its ratio to kPilotReused's on the blocks is already in it, its
/// noise taken kPilotStandardErrors standard errors above its estimate.
bool pilot_decided(std::vector<PilotMeasure> pilot, const std::vector<std::vector<double>>& noise);

/// What another round of the pilot is expected to win back, as a share of the most efficient's
/// efficiency: the chance that it shows another strategy ahead, times by how much (the knowledge
/// gradient). Each other strategy's log efficiency ratio to the most efficient is normal about
/// the pilot's estimate after `passes` passes, with the standard error of pilot_decided (`noise`
/// as there); after kPilotRoundPasses more its error would shrink as 1/sqrt(passes), and its
/// estimate move by what the error loses. The round pays where that moves the other's expected
/// efficiency above the leader's: E[(e^(m' + s'^2/2) - 1)^+] over the estimate m' after it (s' its
/// error then), summed over the others. The pilot stops where a round costs a larger share of
/// the render than this.
double pilot_round_gain(std::vector<PilotMeasure> pilot, const std::vector<std::vector<double>>& noise,
                        unsigned passes);

/// The strategy that renders, and for `auto` why it was chosen.
struct StrategyChoice {
  StrategyOptions options;  ///< as given; for `auto`, with the kind it chose
  /// auto: how much a point drawn by the texels gains over one drawn uniformly on its light, per
  /// sample: E[D(x) / mean density of x's light] for x drawn with density D, 1 where the
  /// emission is flat on every light (the ratio of the two draws' second moments when the
  /// lights' emission dominates). 0 for the other strategies. Reported, not chosen by.
  double texel_gain = 0.0;
  std::vector<PilotMeasure> pilot;  ///< auto: each strategy the pilot weighed; empty otherwise
  std::string reason;  ///< auto: the choice in a sentence; empty for the others
  unsigned pilot_passes = 0;  ///< auto: the passes of each strategy the pilot rendered before it chose
  std::size_t pilot_pixels = 0;  ///< auto: the pixels of the pilot's grid
  /// auto: the pixels of its blocks, on which it weighs kPilotReuse against kPilotReused (0 where
  /// paths do not scatter: restir is ris then, and the pilot does not weigh it)
  std::size_t pilot_block_pixels = 0;
  /// auto: the pilot's most efficient strategy; the cheapest within a margin of it renders
  /// (options.kind).
  std::string most_efficient;
};

/// The strategy `options` names, made by its registered definition. Throws std::invalid_argument
/// when the scene has no lights or `options` names no registered strategy (`auto`: choose first).
/// `emitters` must outlive the strategy; `trs` draws its point lights with their sampler.
std::unique_ptr<LightStrategy> make_light_strategy(Emitters& emitters, const StrategyOptions& options);

inline constexpr lightsampler::EnumName<TreeImportance> kTreeImportanceNames[] = {
    {TreeImportance::pbrt, "pbrt"}, {TreeImportance::cycles, "cycles"}};
inline constexpr lightsampler::EnumName<TreePower> kTreePowerNames[] = {
    {TreePower::exact, "exact"}, {TreePower::image_mean, "image-mean"}};

inline const char* to_string(TreeImportance value) { return lightsampler::name_of(kTreeImportanceNames, value); }
inline const char* to_string(TreePower value) { return lightsampler::name_of(kTreePowerNames, value); }

}  // namespace tracer
