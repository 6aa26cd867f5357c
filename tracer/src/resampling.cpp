#include "resampling.h"

#include <stdexcept>

#include "reuse.h"
#include "strategies/strategies.h"
#include "tracer/strategy_registry.h"

namespace tracer {
namespace {

/// As a strategy, `ris` is its source under another name, with its number of candidates; so is
/// `restir`, with the reuse the renderer gives it (reuse.h).
class ResampledStrategy : public LightStrategy {
 public:
  ResampledStrategy(std::unique_ptr<LightStrategy> source, unsigned candidates, std::optional<ReuseOptions> reuse)
      : source_(std::move(source)), candidates_(candidates), reuse_(reuse) {
    if (candidates_ == 0) throw std::invalid_argument(name() + " needs a candidate");
  }
  std::string name() const override { return reuse_ ? "restir" : "ris"; }
  const ReuseOptions* reuse() const { return reuse_ ? &*reuse_ : nullptr; }
  unsigned candidates() const override { return candidates_; }
  void begin_pass(std::uint64_t seed) override { source_->begin_pass(seed); }
  void emission_changed() override { source_->emission_changed(); }
  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    return source_->sample(random, at);
  }
  void prefetch(const LightRandom& random) const override { source_->prefetch(random); }
  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return source_->pdf(light, b1, b2, from);
  }
  LightPass last_pass() const override { return source_->last_pass(); }
  std::string device() const override { return source_->device(); }
  StrategySetup setup() const override { return source_->setup(); }

 private:
  std::unique_ptr<LightStrategy> source_;
  unsigned candidates_;
  std::optional<ReuseOptions> reuse_;
};

/// The strategy `c.options.candidates_from` names, over every light, resampled.
std::unique_ptr<LightStrategy> resampled(const StrategyContext& c, std::optional<ReuseOptions> reuse) {
  const std::string& source = c.options.candidates_from;
  if (!resamplable(source))
    throw std::invalid_argument((reuse ? "restir" : "ris") + std::string(" cannot draw its candidates from ") + source);
  return std::make_unique<ResampledStrategy>(make_strategy_over_every_light(c.emitters, source, c.options),
                                             c.options.candidates, reuse);
}

TRS_REGISTER_STRATEGY({.name = "ris",
                       .summary = "another strategy's points resampled per shading point",
                       .make = [](const StrategyContext& c) { return resampled(c, std::nullopt); },
                       .resamples = true});
TRS_REGISTER_STRATEGY({.name = "restir",
                       .summary = "ris's reservoirs reused across passes and neighbouring pixels, unbiased",
                       .make = [](const StrategyContext& c) { return resampled(c, reuse_options(c.options.parameters)); },
                       .resamples = true,
                       .parameters = {{"neighbours", "reservoirs of neighbouring pixels reused per pass, at most 64; 8"},
                                      {"radius", "how far those neighbours are, in pixels; 6"},
                                      {"m-cap", "the most a pixel's earlier passes count for, in passes' candidates; 20"},
                                      {"temporal", "on or off: reuse each pixel's reservoir of the pass before; off"},
                                      {"weights", "pairwise or balance (both unbiased; pairwise evaluates 2n targets, balance n(n+2)) or uniform (1/M: biased); pairwise"}}});

}  // namespace

const ReuseOptions* reuse_of(const LightStrategy& strategy) {
  const auto* resampled = dynamic_cast<const ResampledStrategy*>(&strategy);
  return resampled ? resampled->reuse() : nullptr;
}

}  // namespace tracer
