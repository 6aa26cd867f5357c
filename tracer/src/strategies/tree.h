#pragma once
// `tree` with any node importance: make_tree_strategy (strategies.h) with the options' own, and
// other importances for the tests.

#include <memory>

#include "strategies/light_tree.h"

namespace tracer {

std::unique_ptr<LightStrategy> make_tree_strategy(const Emitters& emitters, TreePower power,
                                                  std::unique_ptr<const NodeImportance> importance);

}  // namespace tracer
