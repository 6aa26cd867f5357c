#include "strategies/light_tree.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <tbb/parallel_invoke.h>

#include "luminance.h"
#include "strategies/unit_interval.h"

namespace tracer {
namespace {

constexpr double kPi = std::numbers::pi;
/// Buckets per axis of the split search (pbrt-v4's).
constexpr int kBuckets = 12;
/// The deepest a leaf may lie: its trail holds a bit per level below the root, and the top bit
/// is left for kNotInTree.
constexpr unsigned kMaxDepth = 63;
constexpr std::uint64_t kNotInTree = ~std::uint64_t(0);
/// Subtrees of this many lights or more are built as tasks of their own.
constexpr std::size_t kParallelLights = 1024;

double angle(float cos_theta) { return std::acos(std::clamp(double(cos_theta), -1.0, 1.0)); }

/// The smallest cone that holds both sets' normal cones (pbrt-v4's DirectionCone Union), written
/// into `into`; computed in double, the angles near 0 and pi being acos's least accurate.
void merge_cones(const LightBounds& a, const LightBounds& b, LightBounds& into) {
  const double theta_a = angle(a.cos_theta_o), theta_b = angle(b.cos_theta_o);
  const glm::dvec3 wa(a.axis), wb(b.axis);
  const double theta_d = std::acos(std::clamp(glm::dot(wa, wb), -1.0, 1.0));
  const LightBounds* holder = std::min(theta_d + theta_b, kPi) <= theta_a   ? &a
                              : std::min(theta_d + theta_a, kPi) <= theta_b ? &b
                                                                            : nullptr;
  if (holder) {
    into.axis = holder->axis;
    into.cos_theta_o = holder->cos_theta_o;
    return;
  }
  const double theta_o = (theta_a + theta_d + theta_b) / 2.0;
  const glm::dvec3 k = glm::cross(wa, wb);
  if (theta_o >= kPi || glm::dot(k, k) == 0.0) {  // opposite axes: every direction
    into.axis = a.axis;
    into.cos_theta_o = -1.0f;
    return;
  }
  // a's axis turned towards b's by theta_o - theta_a: the merged cone then touches a's on the
  // side away from b, and b's on the side away from a.
  const double theta_r = theta_o - theta_a;
  const glm::dvec3 w = wa * std::cos(theta_r) + glm::cross(glm::normalize(k), wa) * std::sin(theta_r);
  into.axis = glm::vec3(glm::normalize(w));
  into.cos_theta_o = float(std::cos(theta_o));
}

/// pbrt-v4's M_Omega: the solid angle a set's emission covers, weighed by cosine.
double orientation_measure(const LightBounds& b) {
  const double theta_o = angle(b.cos_theta_o), theta_e = angle(b.cos_theta_e);
  const double theta_w = std::min(theta_o + theta_e, kPi);
  const double cos_o = b.cos_theta_o, sin_o = std::sqrt(std::max(0.0, 1.0 - cos_o * cos_o));
  return 2.0 * kPi * (1.0 - cos_o) +
         kPi / 2.0 * (2.0 * theta_w * sin_o - std::cos(theta_o - 2.0 * theta_w) - 2.0 * theta_o * sin_o + cos_o);
}

double surface_area(const LightBounds& b) {
  const glm::dvec3 d(b.diagonal());
  return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

/// The surface area orientation heuristic's cost of one side of a split along `axis` of a node
/// whose box has diagonal `node_diagonal` (pbrt-v4's EvaluateCost): K_r favours cutting the
/// node's long axis.
double side_cost(const LightBounds& side, glm::vec3 node_diagonal, int axis) {
  const double k_r = double(std::max({node_diagonal.x, node_diagonal.y, node_diagonal.z})) / node_diagonal[axis];
  return side.power * orientation_measure(side) * k_r * surface_area(side);
}

/// Levels below a subtree of n lights split in halves: ceil(log2 n).
unsigned balanced_depth(std::size_t n) { return unsigned(std::bit_width(n - 1)); }

/// One emissive triangle: its corners' box, its normal's cone (every way for two-sided ones),
/// emitting up to 90 degrees from the normal.
LightBounds triangle_bounds(const std::array<glm::vec3, 3>& vertices, glm::vec3 normal,
                            bool two_sided, float power) {
  LightBounds b;
  b.lower = glm::min(vertices[0], glm::min(vertices[1], vertices[2]));
  b.upper = glm::max(vertices[0], glm::max(vertices[1], vertices[2]));
  b.axis = normal;
  b.cos_theta_o = two_sided ? -1.0f : 1.0f;
  b.cos_theta_e = 0.0f;
  b.power = power;
  b.set_derived();
  return b;
}

/// A point or spot light, as pbrt-v4 bounds them: its position; a point light emits every way, a
/// spot within its inner cone at full power and out to its outer cone.
LightBounds punctual_bounds(const PunctualLight& light, float power) {
  LightBounds b;
  b.lower = b.upper = light.position;
  b.axis = light.direction;
  if (light.kind == PunctualLight::Kind::spot) {
    b.cos_theta_o = light.cos_inner;
    b.cos_theta_e = float(std::cos(angle(light.cos_outer) - angle(light.cos_inner)));
  } else {
    b.cos_theta_o = -1.0f;
    b.cos_theta_e = 0.0f;
  }
  b.power = power;
  b.set_derived();
  return b;
}

/// Both sets: boxes and normal cones merged, powers summed. A set of no power is no set.
LightBounds merge(const LightBounds& a, const LightBounds& b) {
  if (!(a.power > 0.0f)) return b;
  if (!(b.power > 0.0f)) return a;
  LightBounds m;
  m.lower = glm::min(a.lower, b.lower);
  m.upper = glm::max(a.upper, b.upper);
  merge_cones(a, b, m);
  m.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  m.power = a.power + b.power;
  m.set_derived();
  return m;
}

}  // namespace

/// The build: each subtree fills the node range its light count gives it (2n - 1 nodes for n
/// lights, its first child's right after it), so the nodes are the same whichever thread builds
/// which subtree.
struct LightTree::Build {
  struct Item {
    LightBounds bounds;
    glm::vec3 centre;
    std::uint32_t light;
  };

  LightTree& tree;

  LightBounds subtree(std::span<Item> items, std::uint32_t node, unsigned depth, std::uint64_t trail) const {
    if (items.size() == 1) {
      tree.nodes_[node] = {items[0].bounds, items[0].light, true};
      tree.trails_[items[0].light] = trail;
      return items[0].bounds;
    }
    const std::size_t mid = split(items, depth);
    const auto second = std::uint32_t(node + 2 * mid);
    LightBounds a, b;
    const auto first_half = [&] { a = subtree(items.first(mid), node + 1, depth + 1, trail); };
    const auto second_half = [&] {
      b = subtree(items.subspan(mid), second, depth + 1, trail | (std::uint64_t(1) << depth));
    };
    if (items.size() >= kParallelLights) {
      tbb::parallel_invoke(first_half, second_half);
    } else {
      first_half();
      second_half();
    }
    tree.nodes_[node] = {merge(a, b), second, false};
    return tree.nodes_[node].bounds;
  }

  /// Reorders `items` into the two children's and returns the first's count: the bucket
  /// boundary of least cost over the three axes, or the middle when the centres do not differ,
  /// or when a child would leave no room for its trail.
  static std::size_t split(std::span<Item> items, unsigned depth) {
    LightBounds box;  // of the node's lights, and of their centres
    glm::vec3 low(std::numeric_limits<float>::infinity()), high(-std::numeric_limits<float>::infinity());
    for (const Item& item : items) {
      box.lower = glm::min(box.lower, item.bounds.lower);
      box.upper = glm::max(box.upper, item.bounds.upper);
      low = glm::min(low, item.centre);
      high = glm::max(high, item.centre);
    }
    const auto bucket = [&](const Item& item, int axis) {
      const float offset = (item.centre[axis] - low[axis]) / (high[axis] - low[axis]);
      return std::min(int(float(kBuckets) * offset), kBuckets - 1);
    };

    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bucket = 0;
    std::size_t best_count = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(high[axis] > low[axis])) continue;
      std::array<LightBounds, kBuckets> buckets;
      std::array<std::size_t, kBuckets> counts{};
      for (const Item& item : items) {
        const int b = bucket(item, axis);
        buckets[b] = merge(buckets[b], item.bounds);
        ++counts[b];
      }
      std::array<LightBounds, kBuckets> above;  // above[i]: buckets i + 1 and up
      for (int i = kBuckets - 2; i >= 0; --i) above[i] = merge(buckets[i + 1], above[i + 1]);
      LightBounds below;
      std::size_t count = 0;
      for (int i = 0; i < kBuckets - 1; ++i) {
        below = merge(below, buckets[i]);
        count += counts[i];
        if (count == 0 || count == items.size()) continue;
        const double cost = side_cost(below, box.diagonal(), axis) + side_cost(above[i], box.diagonal(), axis);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bucket = i;
          best_count = count;
        }
      }
    }
    const auto fits = [&](std::size_t n) { return depth + 1 + balanced_depth(n) <= kMaxDepth; };
    if (best_axis < 0 || !fits(best_count) || !fits(items.size() - best_count)) return items.size() / 2;
    std::partition(items.begin(), items.end(),
                   [&](const Item& item) { return bucket(item, best_axis) <= best_bucket; });
    return best_count;
  }
};

std::vector<double> tree_power(const Emitters& emitters, TreePower source) {
  const PunctualLights& punctual = emitters.punctual();
  std::vector<double> power(emitters.count() + punctual.count(), 0.0);
  for (std::uint32_t light = 0; light < emitters.count(); ++light) {
    const double faces = emitters.two_sided(light) ? 2.0 : 1.0;
    power[light] = source == TreePower::exact ? emitters.power(light) / kPi
                                              : faces * emitters.area(light) * emitters.mean_density(light);
  }
  for (std::uint32_t i = 0; i < punctual.count(); ++i) {
    if (punctual[i].kind != PunctualLight::Kind::directional)
      power[emitters.count() + i] = 4.0 * double(luminance(punctual[i].intensity));
  }
  return power;
}

LightTree::LightTree(const Emitters& emitters, std::span<const double> power) : trails_(power.size(), kNotInTree) {
  std::vector<Build::Item> items;
  for (std::uint32_t light = 0; light < power.size(); ++light) {
    const auto phi = float(power[light]);
    if (!(phi > 0.0f)) continue;  // never sampled: left out
    const LightBounds b = light < emitters.count()
                              ? triangle_bounds(emitters.vertices(light), emitters.normal(light),
                                                emitters.two_sided(light), phi)
                              : punctual_bounds(emitters.punctual()[light - emitters.count()], phi);
    items.push_back({b, b.centre(), light});
  }
  if (items.empty()) return;  // the lights emit nothing (a dark frame)
  nodes_.resize(2 * items.size() - 1);
  Build{*this}.subtree(items, 0, 0, 0);
}

namespace {

/// The probability of walking into child 0 or 1, given the first's: the walk and the pmf both
/// take it from here.
float branch_probability(float first, int child) { return child == 0 ? first : 1.0f - first; }

}  // namespace

std::optional<LightTree::Pick> LightTree::sample(double u, const ShadingPoint& at,
                                                 const NodeImportance& importance) const {
  if (nodes_.empty()) return std::nullopt;
  std::uint32_t index = 0;
  float pmf = 1.0f;
  while (!nodes_[index].leaf) {
    const LightTreeNode& node = nodes_[index];
    const std::optional<float> first = importance.first_child_probability(nodes_[index + 1], nodes_[node.index], at);
    if (!first) return std::nullopt;
    // The child whose share of [0, 1) holds u, and u stretched from that share back onto [0, 1):
    // a walk reads a few bits of u at each level, so it keeps them in double precision.
    const double p = *first;
    const int child = u < p ? 0 : 1;
    u = below_one(child == 0 ? u / p : (u - p) / (1.0 - p));
    pmf *= branch_probability(*first, child);
    index = child == 0 ? index + 1 : node.index;
  }
  return Pick{nodes_[index].index, pmf};
}

float LightTree::pmf(std::uint32_t light, const ShadingPoint& at, const NodeImportance& importance) const {
  std::uint64_t trail = trails_[light];
  if (trail == kNotInTree) return 0.0f;
  std::uint32_t index = 0;
  float pmf = 1.0f;
  while (!nodes_[index].leaf) {
    const LightTreeNode& node = nodes_[index];
    const std::optional<float> first = importance.first_child_probability(nodes_[index + 1], nodes_[node.index], at);
    if (!first) return 0.0f;
    const int child = int(trail & 1);
    pmf *= branch_probability(*first, child);
    index = child == 0 ? index + 1 : node.index;
    trail >>= 1;
  }
  return pmf;
}

std::size_t LightTree::bytes() const {
  return nodes_.capacity() * sizeof(LightTreeNode) + trails_.capacity() * sizeof(std::uint64_t);
}

}  // namespace tracer
