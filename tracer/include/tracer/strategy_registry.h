#pragma once
// The light strategies by name. A strategy is one source file that defines a LightStrategy and
// registers it with TRS_REGISTER_STRATEGY; trs-render's --strategy and its help, the settings
// file, trs-study, the Python module and the tests read the names from here. A plugin is such a
// file compiled outside the tree into a shared library (examples/light_strategy) and loaded by
// load_strategy_plugin (trs-render --plugin): its registrations run as it loads, as Mitsuba 3's
// plugins register themselves.

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tracer/light_strategy.h"

/// Changes whenever a type a plugin sees (LightStrategy, LightLiSample, LightPoint, Emitters, StrategyOptions,
/// StrategyDefinition) changes its layout: a plugin built against other headers is refused.
#define TRS_TRACER_PLUGIN_ABI 2

namespace tracer {

/// What a strategy is made from: the scene's lights and the options of the render.
struct StrategyContext {
  Emitters& emitters;  ///< outlives the strategy
  const StrategyOptions& options;
};

/// An option of a plugin's strategy: trs-render --strategy-option NAME=VALUE, which the strategy
/// reads from StrategyOptions::parameters.
struct StrategyParameter {
  std::string name;
  std::string help;
};

struct StrategyDefinition {
  std::string name;     ///< as --strategy takes it: lower case, digits and '-'
  std::string summary;  ///< what it draws, in a few words, for --strategy's help
  std::function<std::unique_ptr<LightStrategy>(const StrategyContext&)> make;
  /// Draws from the emitters' light sampler every pass (trs-render then subdivides its mesh, and
  /// --lights sizes its point sets).
  bool draws_point_lights = false;
  /// Reads StrategyOptions::tree (--tree-importance, --tree-power).
  bool picks_by_tree = false;
  /// Draws the punctual lights itself, among its choices; otherwise they are drawn beside its
  /// points by power, and it is never made for a scene without emissive triangles.
  bool draws_punctual_lights = false;
  /// Resamples another strategy's points (ris): it cannot be a source of candidates itself.
  bool resamples = false;
  /// The options it reads from StrategyOptions::parameters; trs-render refuses any other.
  std::vector<StrategyParameter> parameters = {};
  /// The shared library it was loaded from (load_strategy_plugin); empty for the program's own.
  std::filesystem::path plugin = {};
};

/// The name that is no strategy of its own: it chooses one for the scene (choose_strategy).
inline constexpr const char* kAutoStrategy = "auto";

/// Adds `definition`. Throws std::invalid_argument for a name taken or malformed, or without a
/// `make`.
void register_strategy(StrategyDefinition definition);

/// The strategy registered as `name`; null for none.
const StrategyDefinition* find_strategy(const std::string& name);

/// Every registered strategy, in the order of their names.
std::vector<const StrategyDefinition*> registered_strategies();

/// The names --strategy takes: every registered strategy's, then `auto`.
std::vector<std::string> strategy_names();

/// Loads the strategies of the shared library `file` (built against this version's headers). A
/// file loaded before is not loaded again. Throws FileError naming the file when it cannot be
/// loaded, registers nothing, or registers a name already taken.
void load_strategy_plugin(const std::filesystem::path& file);

/// Registers a definition when its translation unit is loaded: `TRS_REGISTER_STRATEGY({...})`.
struct StrategyRegistration {
  StrategyRegistration(StrategyDefinition definition, int abi);
};

}  // namespace tracer

#define TRS_STRATEGY_CONCAT2(a, b) a##b
#define TRS_STRATEGY_CONCAT(a, b) TRS_STRATEGY_CONCAT2(a, b)
/// Registers a StrategyDefinition as this file is loaded (the program starts, or the plugin is
/// opened).
#define TRS_REGISTER_STRATEGY(...)                                                              \
  static const ::tracer::StrategyRegistration TRS_STRATEGY_CONCAT(trs_strategy_registration_, \
                                                                  __LINE__)(                  \
      ::tracer::StrategyDefinition __VA_ARGS__, TRS_TRACER_PLUGIN_ABI)
