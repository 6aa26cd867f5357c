#include "tracer/light_strategy.h"

#include <stdexcept>

#include "resampling.h"
#include "strategies/strategies.h"

namespace tracer {

namespace {

std::unique_ptr<LightStrategy> make_source(Emitters& emitters, StrategyKind kind,
                                           const StrategyOptions& options) {
  switch (kind) {
    case StrategyKind::uniform:
    case StrategyKind::power:
    case StrategyKind::tree:
    case StrategyKind::tree_texel: return make_chosen_light_strategy(emitters, kind, options.tree);
    case StrategyKind::trs: return make_trs_strategy(emitters, options);
    case StrategyKind::texel: return make_texel_strategy(emitters);
    case StrategyKind::ris:
    case StrategyKind::automatic: break;
  }
  throw std::invalid_argument(std::string("no light strategy made as ") + to_string(kind));
}

/// The strategy `kind` over the emissive triangles and the punctual lights: the tree holds them
/// among its leaves; the others take them beside their draws, by power, as every strategy does
/// where no triangle emits.
std::unique_ptr<LightStrategy> make_lights(Emitters& emitters, StrategyKind kind,
                                           const StrategyOptions& options) {
  const bool tree = kind == StrategyKind::tree || kind == StrategyKind::tree_texel;
  if (emitters.punctual().count() == 0 || (tree && emitters.count() > 0)) return make_source(emitters, kind, options);
  return with_punctual_lights(emitters, emitters.count() > 0 ? make_source(emitters, kind, options) : nullptr,
                              to_string(kind));
}

}  // namespace

bool resamplable(StrategyKind kind) { return kind != StrategyKind::ris && kind != StrategyKind::automatic; }

std::unique_ptr<LightStrategy> make_light_strategy(Emitters& emitters, const StrategyOptions& options) {
  if (emitters.count() == 0 && emitters.punctual().count() == 0)
    throw std::invalid_argument("the scene has no lights: no emissive triangle and no punctual light");
  if (options.kind != StrategyKind::ris) return make_lights(emitters, options.kind, options);
  if (!resamplable(options.candidates_from))
    throw std::invalid_argument(std::string("ris cannot draw its candidates from ") +
                                to_string(options.candidates_from));
  return make_resampled(make_lights(emitters, options.candidates_from, options), options.candidates);
}

LightSample light_point(const Emitters& emitters, std::uint32_t light, float b1, float b2,
                        float pdf, float mis_pdf) {
  const glm::vec3 radiance = emitters.emission(light, b1, b2) * emitters.opacity(light, b1, b2);
  return {emitters.position(light, b1, b2), pdf, emitters.normal(light), mis_pdf, radiance, light,
          b1, b2, emitters.two_sided(light)};
}

const char* to_string(StrategyKind kind) {
  for (const StrategyName& s : kStrategyNames)
    if (s.kind == kind) return s.name;
  return "?";
}

std::optional<StrategyKind> parse_strategy(const std::string& name) {
  for (const StrategyName& s : kStrategyNames)
    if (name == s.name) return s.kind;
  return std::nullopt;
}

const char* to_string(TreeImportance importance) {
  return importance == TreeImportance::pbrt ? "pbrt" : "cycles";
}

const char* to_string(TreePower power) { return power == TreePower::exact ? "exact" : "image-mean"; }

}  // namespace tracer
