#pragma once
// The strategies behind make_light_strategy.

#include <memory>
#include <string>

#include "tracer/light_strategy.h"

namespace tracer {

class LightChoice;
class TrianglePoint;

/// A light chosen by `choice`, then a point on a chosen triangle by `point` (chosen_light.cpp).
std::unique_ptr<LightStrategy> make_chosen_light_strategy(const Emitters& emitters, std::unique_ptr<LightChoice> choice,
                                                          std::unique_ptr<TrianglePoint> point, std::string name);
/// The registered strategy `name` over the emissive triangles and the punctual lights: one that
/// draws punctual lights itself (the tree) holds them among its choices; the punctual lights are
/// drawn beside the others' points, by power, as every strategy does where no triangle emits.
std::unique_ptr<LightStrategy> make_strategy_over_every_light(Emitters& emitters, const std::string& name,
                                                              const StrategyOptions& options);

/// `area`'s draws over the emissive triangles (none where no triangle emits) and the scene's
/// punctual lights beside them, chosen by power (punctual.cpp); named `name`.
std::unique_ptr<LightStrategy> with_punctual_lights(const Emitters& emitters, std::unique_ptr<LightStrategy> area,
                                                    std::string name);
/// Punctual light `light` seen from `at`, chosen with probability `pmf`: a delta sample of the
/// irradiance it brings; none where it brings nothing.
std::optional<LightLiSample> punctual_sample(const Emitters& emitters, std::uint32_t light, double pmf,
                                             const ShadingPoint& at);

}  // namespace tracer
