#pragma once
// How much a node of the light tree may bring to a shading point, from its bounds alone: what
// the walk weighs a node's two children with.
//
// - pbrt (pbrt-v4's LightBounds::Importance): one estimate per child, Phi cos(theta') cos(theta'_i)
//   / d^2 with every angle widened by the node's extent, and the children picked in proportion.
// - cycles (Cycles' light tree, kernel/light/tree.h): a lower and an upper bound per child, the
//   first child's probability the mean of its share of the upper bounds and its share of the
//   lower ones.
//
// Both take the cosine at the receiver as |cos|: the tracer's surfaces reflect on either side,
// and a shading point does not say which side its path is on.

#include <memory>
#include <optional>

#include "strategies/light_tree.h"

namespace tracer {

/// pbrt-v4's importance of a set of lights seen from `at`; zero where none of them can emit
/// towards it.
float pbrt_importance(const LightBounds& bounds, const ShadingPoint& at);

/// The first of two children's probability when they are picked in proportion to `first` and
/// `second`; none when both are zero.
inline std::optional<float> proportional(float first, float second) {
  const float total = first + second;
  if (!(total > 0.0f)) return std::nullopt;
  return first / total;
}

/// The importance `kind`. Cycles' reads a leaf's triangle from `emitters`, which must outlive it.
std::unique_ptr<NodeImportance> make_node_importance(TreeImportance kind, const Emitters& emitters);

}  // namespace tracer
