// `texel`: at every next-event query, a texel piece of the lights drawn in proportion to its
// density times its area (an alias table over the scene's pieces, piece_table.h), then a uniform
// point in it. Its density is D(x) / integral of D, the target density of `trs`, drawn exactly at
// each query: `trs` with infinitely many lights per frame. Comparing the two separates what the
// target density is worth from what the per-frame point set costs and gives.

#include <chrono>
#include <optional>

#include <lightsampler/random.h>

#include "strategies/alias_table.h"
#include "strategies/piece_table.h"
#include "strategies/strategies.h"
#include "strategies/unit_interval.h"
#include "tracer/strategy_registry.h"

namespace tracer {
namespace {

class TexelStrategy : public LightStrategy {
 public:
  explicit TexelStrategy(const Emitters& emitters) : emitters_(emitters) { build(); }

  std::string name() const override { return "texel"; }
  void emission_changed() override { build(); }

  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    if (!alias_) return std::nullopt;  // the lights emit nothing
    const alias::Pick pick = alias_->sample(word64(random, 0));
    const std::uint32_t light = table_->light(pick.index);
    const lightsampler::Barycentrics b = table_->point(pick.index, below_one_float(pick.u),
                                                       lightsampler::uniform_float(random[2]),
                                                       lightsampler::uniform_float(random[3]));
    // Rounding can put a point on its cell's edge into the neighbouring texel: its density is
    // what that texel reads, as pdf() gives it; one without density carries nothing.
    const float p = density(light, b.b1, b.b2);
    if (!(p > 0.0f)) return std::nullopt;
    return seen_from(emitters_, light_point(emitters_, light, b.b1, b.b2, p, p), at);
  }

  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint&) const override {
    return density(light, b1, b2);
  }

  StrategySetup setup() const override { return {build_ms_, table_->bytes() + (alias_ ? alias_->bytes() : 0)}; }

 private:
  void build() {
    const auto start = std::chrono::steady_clock::now();
    table_.emplace(emitters_);
    alias_.reset();
    if (table_->total_weight() > 0.0) alias_.emplace(table_->weights());
    build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  float density(std::uint32_t light, float b1, float b2) const {
    const double total = table_->total_weight();
    return total > 0.0 ? float(double(emitters_.density(light, b1, b2)) / total) : 0.0f;
  }

  const Emitters& emitters_;
  std::optional<PieceTable> table_;
  std::optional<alias::Table> alias_;  ///< none when the lights emit nothing
  double build_ms_ = 0.0;
};

TRS_REGISTER_STRATEGY({.name = "texel",
                       .summary = "texel pieces of the lights by their emission",
                       .make = [](const StrategyContext& c) { return std::make_unique<TexelStrategy>(c.emitters); }});

}  // namespace

}  // namespace tracer
