#include "resampling.h"

#include <stdexcept>

#include "strategies/strategies.h"
#include "tracer/strategy_registry.h"

namespace tracer {
namespace {

/// As a strategy, `ris` is its source under another name, with its number of candidates.
class ResampledStrategy : public LightStrategy {
 public:
  ResampledStrategy(std::unique_ptr<LightStrategy> source, unsigned candidates)
      : source_(std::move(source)), candidates_(candidates) {
    if (candidates_ == 0) throw std::invalid_argument("ris needs a candidate");
  }
  std::string name() const override { return "ris"; }
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
};

TRS_REGISTER_STRATEGY({.name = "ris",
                       .summary = "another strategy's points resampled per shading point",
                       .make = [](const StrategyContext& c) -> std::unique_ptr<LightStrategy> {
                         const std::string& source = c.options.candidates_from;
                         if (!resamplable(source))
                           throw std::invalid_argument("ris cannot draw its candidates from " + source);
                         return make_resampled(make_strategy_over_every_light(c.emitters, source, c.options),
                                               c.options.candidates);
                       },
                       .resamples = true});

}  // namespace

std::unique_ptr<LightStrategy> make_resampled(std::unique_ptr<LightStrategy> source, unsigned candidates) {
  return std::make_unique<ResampledStrategy>(std::move(source), candidates);
}

}  // namespace tracer
