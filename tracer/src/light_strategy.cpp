#include "tracer/light_strategy.h"

#include <stdexcept>

#include "strategies/strategies.h"

namespace tracer {

std::unique_ptr<LightStrategy> make_light_strategy(const Emitters& emitters,
                                                   const StrategyOptions& options) {
  if (emitters.count() == 0)
    throw std::invalid_argument("the scene has no emissive triangles to sample");
  switch (options.kind) {
    case StrategyKind::uniform: return make_uniform_strategy(emitters);
    case StrategyKind::power: return make_power_strategy(emitters);
    case StrategyKind::trs: return make_trs_strategy(emitters, options);
  }
  throw std::invalid_argument("unknown light strategy");
}

const char* to_string(StrategyKind kind) {
  switch (kind) {
    case StrategyKind::uniform: return "uniform";
    case StrategyKind::power: return "power";
    case StrategyKind::trs: return "trs";
  }
  return "?";
}

std::optional<StrategyKind> parse_strategy(const std::string& name) {
  for (StrategyKind kind : {StrategyKind::uniform, StrategyKind::power, StrategyKind::trs})
    if (name == to_string(kind)) return kind;
  return std::nullopt;
}

}  // namespace tracer
