#include "tracer/strategy_registry.h"

#include <dlfcn.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "scene_io/file_error.h"

namespace tracer {
namespace {

/// A plugin being opened: its registrations run inside dlopen, where nothing may throw, so they
/// are collected here and checked once dlopen returns.
struct PluginLoad {
  std::vector<StrategyDefinition> definitions;
  std::vector<std::string> problems;
};

struct Registry {
  std::recursive_mutex mutex;
  std::map<std::string, StrategyDefinition> strategies;
  std::vector<std::filesystem::path> plugins;  ///< loaded, as canonical paths
  PluginLoad* loading = nullptr;
};

Registry& registry() {
  static Registry instance;  // built on first use: registrations run during static initialisation
  return instance;
}

/// Why `definition` cannot be registered beside the strategies there are; none if it can.
std::optional<std::string> refusal(const Registry& r, const StrategyDefinition& definition) {
  const std::string& name = definition.name;
  const bool well_formed =
      !name.empty() && name[0] >= 'a' && name[0] <= 'z' &&
      std::all_of(name.begin(), name.end(), [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-'; });
  if (!well_formed) return "strategy name \"" + name + "\" is not lower-case letters, digits and '-', from a letter";
  if (name == kAutoStrategy || r.strategies.count(name) > 0) return "a strategy named " + name + " exists already";
  if (!definition.make) return "strategy " + name + " has no make function";
  return std::nullopt;
}

}  // namespace

void register_strategy(StrategyDefinition definition) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  if (const auto problem = refusal(r, definition)) throw std::invalid_argument(*problem);
  std::string name = definition.name;
  r.strategies.emplace(std::move(name), std::move(definition));
}

StrategyRegistration::StrategyRegistration(StrategyDefinition definition, int abi) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  if (r.loading) {
    if (abi != TRS_TRACER_PLUGIN_ABI)
      r.loading->problems.push_back("built against tracer headers of plugin ABI " + std::to_string(abi) +
                                    ", this program has " + std::to_string(TRS_TRACER_PLUGIN_ABI) +
                                    ": rebuild it against this version");
    else
      r.loading->definitions.push_back(std::move(definition));
    return;
  }
  register_strategy(std::move(definition));  // the program's own: a clash is a bug, found at start
}

const StrategyDefinition* find_strategy(const std::string& name) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  const auto found = r.strategies.find(name);
  return found == r.strategies.end() ? nullptr : &found->second;
}

std::vector<const StrategyDefinition*> registered_strategies() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  std::vector<const StrategyDefinition*> all;
  for (const auto& [name, definition] : r.strategies) all.push_back(&definition);
  return all;
}

std::vector<std::string> strategy_names() {
  std::vector<std::string> names;
  for (const StrategyDefinition* s : registered_strategies()) names.push_back(s->name);
  names.emplace_back(kAutoStrategy);
  return names;
}

void load_strategy_plugin(const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::canonical(file, error);
  if (error) throw trs::FileError(file, "cannot load strategy plugin: " + error.message());
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  if (std::find(r.plugins.begin(), r.plugins.end(), canonical) != r.plugins.end()) return;

  // A plugin's references to the tracer resolve against the program or module that holds this
  // registry; a Python extension module is loaded with its symbols local, so make them global.
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&registry), &self) && self.dli_fname)
    dlopen(self.dli_fname, RTLD_NOW | RTLD_NOLOAD | RTLD_GLOBAL);

  PluginLoad load;
  r.loading = &load;
  // RTLD_GLOBAL: a plugin may link libraries of its own that later plugins share.
  void* handle = dlopen(canonical.c_str(), RTLD_NOW | RTLD_GLOBAL);
  r.loading = nullptr;
  if (!handle) throw trs::FileError(file, std::string("cannot load strategy plugin: ") + dlerror());
  if (load.problems.empty() && load.definitions.empty())
    load.problems.emplace_back("registers no strategy (TRS_REGISTER_STRATEGY)");
  for (auto d = load.definitions.begin(); d != load.definitions.end(); ++d) {
    if (const auto problem = refusal(r, *d)) load.problems.push_back(*problem);
    if (std::any_of(load.definitions.begin(), d, [&](const StrategyDefinition& e) { return e.name == d->name; }))
      load.problems.push_back("registers two strategies named " + d->name);
  }
  if (!load.problems.empty()) {
    load.definitions.clear();  // their functions live in the library about to be closed
    dlclose(handle);
    throw trs::FileError(file, "strategy plugin refused: " + load.problems.front());
  }
  for (StrategyDefinition& d : load.definitions) {
    d.plugin = canonical;
    register_strategy(std::move(d));
  }
  r.plugins.push_back(canonical);
}

}  // namespace tracer
