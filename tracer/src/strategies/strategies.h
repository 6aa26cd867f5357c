#pragma once
// The strategies behind make_light_strategy.

#include <memory>
#include <string>

#include "tracer/light_strategy.h"

namespace tracer {

class LightChoice;
class PointDraw;

/// A light chosen by `choice`, then a point on it by `point` (chosen_light.cpp).
std::unique_ptr<LightStrategy> make_chosen_light_strategy(const Emitters& emitters, std::unique_ptr<LightChoice> choice,
                                                          std::unique_ptr<PointDraw> point, std::string name);
/// The registered strategy `name` over the emissive triangles and the punctual lights: one that
/// draws punctual lights itself (the tree) holds them among its choices; the punctual lights are
/// drawn beside the others' points, by power, as every strategy does where no triangle emits.
std::unique_ptr<LightStrategy> make_strategy_over_every_light(Emitters& emitters, const std::string& name,
                                                              const StrategyOptions& options);

/// The emissive triangles as one light beside each punctual light, by power, its points drawn by
/// `triangles` (none where no triangle emits); named `name` (chosen_light.cpp).
std::unique_ptr<LightStrategy> with_punctual_lights(const Emitters& emitters, std::unique_ptr<LightStrategy> triangles,
                                                    std::string name);

}  // namespace tracer
