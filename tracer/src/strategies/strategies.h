#pragma once
// The strategies behind make_light_strategy, one file each.

#include <memory>

#include "tracer/light_strategy.h"

namespace tracer {

std::unique_ptr<LightStrategy> make_uniform_strategy(const Emitters& emitters);
std::unique_ptr<LightStrategy> make_power_strategy(const Emitters& emitters);
std::unique_ptr<LightStrategy> make_trs_strategy(const Emitters& emitters,
                                                 const StrategyOptions& options);
std::unique_ptr<LightStrategy> make_tree_strategy(const Emitters& emitters,
                                                  const StrategyOptions& options);
std::unique_ptr<LightStrategy> make_texel_strategy(const Emitters& emitters);
std::unique_ptr<LightStrategy> make_tree_texel_strategy(const Emitters& emitters,
                                                        const StrategyOptions& options);

}  // namespace tracer
