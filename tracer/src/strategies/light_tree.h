#pragma once
// A bounding volume hierarchy over the emissive triangles and the point and spot lights, one light per leaf, each node bounding
// where its lights are, which way they emit and how much (Conty Estevez and Kulla, "Importance
// Sampling of Many Lights with Adaptive Tree Splitting", 2018; pbrt-v4's BVHLightSampler). From a
// shading point, a walk from the root picks a light, choosing at each node between its two
// children with the probabilities a NodeImportance gives (tree_importance.h).
//
// Built top-down: each node's lights split where the surface area orientation heuristic is
// least, over 12 bins of their centres per axis (pbrt-v4's).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "tracer/emitters.h"
#include "tracer/light_strategy.h"

namespace tracer {

/// A set of lights: their box, the cone of their normals (within theta_o of `axis`), how far
/// from its normal each emits (theta_e), and their power in luminance.
struct LightBounds {
  glm::vec3 lower{std::numeric_limits<float>::infinity()};
  glm::vec3 upper{-std::numeric_limits<float>::infinity()};
  glm::vec3 axis{0.0f, 0.0f, 1.0f};  ///< unit
  float cos_theta_o = 1.0f;
  float cos_theta_e = 1.0f;
  float power = 0.0f;
  // What a walk would otherwise compute at every node, kept by set_derived().
  float sin_theta_o = 0.0f;
  float radius = 0.0f;  ///< of the box's bounding sphere, |diagonal| / 2

  glm::vec3 centre() const { return 0.5f * (lower + upper); }
  glm::vec3 diagonal() const { return upper - lower; }
  /// Sets sin_theta_o and radius from the others.
  void set_derived() {
    sin_theta_o = std::sqrt(std::max(0.0f, 1.0f - cos_theta_o * cos_theta_o));
    radius = 0.5f * glm::length(diagonal());
  }
  bool operator==(const LightBounds&) const = default;
};

struct LightTreeNode {
  LightBounds bounds;
  /// A leaf's light; an interior node's second child (its first is the next node).
  std::uint32_t index = 0;
  bool leaf = false;
  bool operator==(const LightTreeNode&) const = default;
};

/// How a walk down the tree weighs a node's two children from a shading point.
class NodeImportance {
 public:
  virtual ~NodeImportance() = default;
  /// The probability of walking into the first child rather than the second, in [0, 1]; none
  /// when neither can light `at`.
  virtual std::optional<float> first_child_probability(const LightTreeNode& first,
                                                       const LightTreeNode& second,
                                                       const ShadingPoint& at) const = 0;
};

/// What the tree weighs each light by, the triangles' then the punctual lights' (pbrt-v4's
/// LightBounds::phi, on one scale): a bound of its intensity, which for a triangle is its power
/// over pi (Emitters::power: its radiance times its area, face by face) and for a point light
/// 4 I, its power over pi too; a spot light is bounded as the point light of its intensity, its
/// cone saying where it shines. Zero for directional lights, which the tree leaves out.
std::vector<double> tree_power(const Emitters& emitters, TreePower source);

class LightTree {
 public:
  /// Over the lights whose `power` (one per light, numbered as tree_power numbers them) is
  /// positive; empty when none is (nothing is sampled).
  LightTree(const Emitters& emitters, std::span<const double> power);

  struct Pick {
    std::uint32_t light;
    float pmf;  ///< the product of the probabilities of the children walked into
  };
  /// A light for `at`, from a uniform `u` in [0, 1); none when no light can reach it.
  std::optional<Pick> sample(double u, const ShadingPoint& at, const NodeImportance& importance) const;
  /// The probability that sample() picks `light` for `at`: the same walk's probabilities, bit for
  /// bit. Zero for lights outside the tree.
  float pmf(std::uint32_t light, const ShadingPoint& at, const NodeImportance& importance) const;

  /// Parents before their children, a subtree's nodes contiguous.
  std::span<const LightTreeNode> nodes() const { return nodes_; }
  std::size_t bytes() const;

 private:
  struct Build;
  std::vector<LightTreeNode> nodes_;
  /// Per light, the children its walk takes from the root: bit d for depth d, set for the second.
  std::vector<std::uint64_t> trails_;
};

}  // namespace tracer
