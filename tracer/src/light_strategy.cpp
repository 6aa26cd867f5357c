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
    case StrategyKind::trs:
    case StrategyKind::ris: return make_trs_strategy(emitters, options);
  }
  throw std::invalid_argument("unknown light strategy");
}

LightSample light_point(const Emitters& emitters, std::uint32_t light, float b1, float b2,
                        float pdf, float mis_pdf) {
  return {emitters.position(light, b1, b2), pdf,       emitters.normal(light),
          mis_pdf,                          emitters.emission(light, b1, b2), light,
          b1,                               b2,        emitters.two_sided(light)};
}

const char* to_string(StrategyKind kind) {
  switch (kind) {
    case StrategyKind::uniform: return "uniform";
    case StrategyKind::power: return "power";
    case StrategyKind::trs: return "trs";
    case StrategyKind::ris: return "ris";
  }
  return "?";
}

std::optional<StrategyKind> parse_strategy(const std::string& name) {
  for (StrategyKind kind :
       {StrategyKind::uniform, StrategyKind::power, StrategyKind::trs, StrategyKind::ris})
    if (name == to_string(kind)) return kind;
  return std::nullopt;
}

}  // namespace tracer
