#include "tracer/light_strategy.h"

#include <stdexcept>

#include "strategies/strategies.h"
#include "tracer/strategy_registry.h"

namespace tracer {

namespace {

const StrategyDefinition& definition(const std::string& name) {
  const StrategyDefinition* found = find_strategy(name);
  if (!found) throw std::invalid_argument("no light strategy named " + name + " (strategy_names() lists them)");
  return *found;
}

}  // namespace

const std::string& source_kind(const StrategyOptions& options) {
  const StrategyDefinition* named = find_strategy(options.kind);
  return named && named->resamples ? options.candidates_from : options.kind;
}

bool picks_by_tree(const StrategyOptions& options) {
  const StrategyDefinition* source = find_strategy(source_kind(options));
  return source && source->picks_by_tree;
}

bool draws_point_lights(const StrategyOptions& options) {
  const StrategyDefinition* source = find_strategy(source_kind(options));
  return source && source->draws_point_lights;
}

bool resamplable(const std::string& name) {
  const StrategyDefinition* s = find_strategy(name);
  return s && !s->resamples;
}

std::unique_ptr<LightStrategy> make_strategy_over_every_light(Emitters& emitters, const std::string& name,
                                                              const StrategyOptions& options) {
  const StrategyDefinition& d = definition(name);
  const StrategyContext context{emitters, options};
  if (emitters.punctual().count() == 0 || (d.draws_punctual_lights && emitters.count() > 0) || d.resamples)
    return d.make(context);
  return with_punctual_lights(emitters, emitters.count() > 0 ? d.make(context) : nullptr, d.name);
}

std::unique_ptr<LightStrategy> make_light_strategy(Emitters& emitters, const StrategyOptions& options) {
  if (emitters.count() == 0 && emitters.punctual().count() == 0)
    throw std::invalid_argument("the scene has no lights: no emissive triangle and no punctual light");
  return make_strategy_over_every_light(emitters, options.kind, options);
}

LightPoint light_point(const Emitters& emitters, std::uint32_t light, float b1, float b2,
                       float pdf, float mis_pdf) {
  return emitters.light(light).point(b1, b2, pdf, mis_pdf);
}

std::optional<LightLiSample> seen_from(const Emitters& emitters, const LightPoint& point, const ShadingPoint& at) {
  return emitters.light(point.light).sample_li(point, at);
}

}  // namespace tracer
