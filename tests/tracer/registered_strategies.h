#pragma once
// The strategies the statistical tests run over: every one the registry holds, so that a strategy
// added to the tree is tested without a test of its own. Where TRS_STRATEGY_PLUGIN names plugins
// (paths separated by ':'), they are loaded and only their strategies are tested
// (tools/test-strategy-plugin.sh).

#include <cstdlib>
#include <string>
#include <vector>

#include "tracer/strategy_registry.h"

namespace trs_test {

inline const std::vector<std::string>& every_strategy() {
  static const std::vector<std::string> names = [] {
    const char* plugins = std::getenv("TRS_STRATEGY_PLUGIN");
    const std::string list = plugins ? plugins : "";
    for (std::size_t start = 0; start < list.size();) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      if (end > start) tracer::load_strategy_plugin(list.substr(start, end - start));
      start = end + 1;
    }
    std::vector<std::string> result;
    for (const tracer::StrategyDefinition* s : tracer::registered_strategies())
      if (list.empty() || !s->plugin.empty()) result.push_back(s->name);
    return result;
  }();
  return names;
}

}  // namespace trs_test
