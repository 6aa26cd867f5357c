#pragma once
// The light tree as the strategies that pick lights with it hold it: `tree` (a point on the light
// by solid angle or area) and `tree-texel` (a point by the light's texture). make_tree_strategy
// with an importance of its own is for the tests.

#include <chrono>
#include <memory>
#include <optional>
#include <span>

#include "strategies/light_tree.h"

namespace tracer {

/// A light tree with the node importance its walks use, its build timed.
class TreePicker {
 public:
  TreePicker(const Emitters& emitters, std::span<const double> power,
             std::unique_ptr<const NodeImportance> importance)
      : importance_(std::move(importance)), tree_(timed_build(emitters, power)) {}

  /// A light for `at` from `u` uniform in [0, 1), with its pmf; none when none can light `at`.
  std::optional<LightTree::Pick> pick(double u, const ShadingPoint& at) const {
    return tree_.sample(u, at, *importance_);
  }
  /// The probability pick() gives `light` for `at`, bit for bit.
  float pmf(std::uint32_t light, const ShadingPoint& at) const { return tree_.pmf(light, at, *importance_); }

  StrategySetup setup() const { return {build_ms_, tree_.bytes()}; }

  /// The lights' powers changed: the tree is built again, as a fresh one over them would be (a
  /// refit would keep a topology chosen for the old powers, and a frame would then depend on
  /// the frames before it).
  void update(const Emitters& emitters, std::span<const double> power) { tree_ = timed_build(emitters, power); }

 private:
  LightTree timed_build(const Emitters& emitters, std::span<const double> power) {
    const auto start = std::chrono::steady_clock::now();
    LightTree tree(emitters, power);
    build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return tree;
  }

  std::unique_ptr<const NodeImportance> importance_;
  double build_ms_ = 0.0;
  LightTree tree_;
};

std::unique_ptr<LightStrategy> make_tree_strategy(const Emitters& emitters, TreePower power,
                                                  std::unique_ptr<const NodeImportance> importance);

}  // namespace tracer
