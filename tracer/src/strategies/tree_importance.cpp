#include "strategies/tree_importance.h"

#include <algorithm>
#include <cmath>

namespace tracer {
namespace {

float sin_from_cos(float cos_theta) { return std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta)); }

/// cos(max(0, a - b)) for angles a, b in [0, pi], from their cosines and sines.
float cos_minus_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}

/// sin(max(0, a - b)) likewise.
float sin_minus_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

class PbrtImportance : public NodeImportance {
 public:
  std::optional<float> first_child_probability(const LightTreeNode& first, const LightTreeNode& second,
                                               const ShadingPoint& at) const override {
    return proportional(pbrt_importance(first.bounds, at), pbrt_importance(second.bounds, at));
  }
};

/// A node as Cycles' importance sees it from a point.
struct Extent {
  glm::vec3 to_centre;  ///< unit, from the point towards the node's centre (zero at the centre)
  float cos_theta_u;    ///< every direction from the point into the node is within theta_u of to_centre
  float min_distance;
  float max_distance;
};

/// Unit `v`, or zero for a zero `v` (Cycles' safe_normalize).
glm::vec3 safe_direction(glm::vec3 v) {
  const float length = glm::length(v);
  return length > 0.0f ? v / length : glm::vec3(0.0f);
}

/// Cycles clamps a cluster's distance below by half its box's half-diagonal, so that a point
/// inside does not weigh it without bound.
float clamped_distance(const LightBounds& b, float distance) {
  return std::max(0.5f * glm::length(b.upper - b.centre()), distance);
}

/// A cluster of lights (Cycles' light_tree_node_importance): seen within the cone around its
/// box's centre that holds its corners, at the centre's distance.
Extent box_extent(const LightBounds& b, glm::vec3 p) {
  const glm::vec3 centre = b.centre();
  const float distance = glm::length(centre - p);
  const glm::vec3 to_centre = safe_direction(centre - p);
  float cos_theta_u = 1.0f;
  if (glm::all(glm::greaterThan(p, b.lower)) && glm::all(glm::lessThan(p, b.upper))) {
    cos_theta_u = -1.0f;  // inside: every direction
  } else {
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 corner((i & 1) ? b.upper.x : b.lower.x, (i & 2) ? b.upper.y : b.lower.y,
                             (i & 4) ? b.upper.z : b.lower.z);
      cos_theta_u = std::min(cos_theta_u, glm::dot(to_centre, safe_direction(corner - p)));
    }
  }
  const float d = clamped_distance(b, distance);
  return {to_centre, cos_theta_u, d, d};
}

/// One triangle (Cycles' triangle_light_tree_parameters): the cone around its centroid that
/// holds its corners, between the centroid's distance and the farthest corner's. Cycles leaves
/// the near distance unclamped, which is infinite importance at the centroid; it is clamped here
/// as a cluster's is.
Extent triangle_extent(const std::array<glm::vec3, 3>& v, const LightBounds& b, glm::vec3 p) {
  const glm::vec3 centroid = (v[0] + v[1] + v[2]) / 3.0f;
  const float distance = glm::length(centroid - p);
  Extent e{safe_direction(centroid - p), 1.0f, clamped_distance(b, distance), distance};
  for (const glm::vec3& corner : v) {
    e.cos_theta_u = std::min(e.cos_theta_u, glm::dot(e.to_centre, safe_direction(corner - p)));
    e.max_distance = std::max(e.max_distance, glm::length(corner - p));
  }
  e.max_distance = std::max(e.max_distance, e.min_distance);
  return e;
}

struct ImportanceRange {
  float min = 0.0f;
  float max = 0.0f;
};

/// Cycles' light_tree_importance for a receiving surface: the upper bound takes every angle at
/// its most favourable within the node's extent and the near distance, the lower bound every
/// angle at its least favourable and the far distance (zero where some light of the node may
/// face away).
ImportanceRange cycles_range(const LightBounds& b, const Extent& e, glm::vec3 normal) {
  const float cos_u = e.cos_theta_u, sin_u = sin_from_cos(cos_u);
  const float cos_i = std::abs(glm::dot(e.to_centre, normal)), sin_i = sin_from_cos(cos_i);
  const float cos_min_incidence = cos_i >= cos_u ? 1.0f : cos_i * cos_u + sin_i * sin_u;
  const float cos_max_incidence = std::max(cos_i * cos_u - sin_i * sin_u, 0.0f);

  // theta: between the cone's axis and the direction from the node to the point.
  const float cos_theta = std::clamp(glm::dot(b.axis, -e.to_centre), -1.0f, 1.0f), sin_theta = sin_from_cos(cos_theta);
  const float cos_o = b.cos_theta_o, sin_o = b.sin_theta_o;
  const float cos_e = b.cos_theta_e, sin_e = sin_from_cos(cos_e);
  const float cos_theta_minus_u = cos_theta * cos_u + sin_theta * sin_u;
  float cos_min_outgoing;
  if (cos_theta >= cos_u || cos_theta_minus_u >= cos_o) {  // theta - theta_u - theta_o <= 0
    cos_min_outgoing = 1.0f;
  } else if (cos_e < -cos_o || cos_theta_minus_u > cos_o * cos_e - sin_o * sin_e) {
    // theta_o + theta_e > pi, or theta - theta_u < theta_o + theta_e
    cos_min_outgoing = cos_theta_minus_u * cos_o + sin_from_cos(cos_theta_minus_u) * sin_o;
  } else {
    return {};  // no light of the node emits towards the point
  }
  ImportanceRange r;
  r.max = std::abs(cos_min_incidence * b.power * cos_min_outgoing / (e.min_distance * e.min_distance));

  // theta + theta_u + theta_o within theta_e, or the lower bound is zero.
  const float cos_theta_plus_u = cos_theta * cos_u - sin_theta * sin_u;
  if (cos_e > cos_o || cos_theta < 0.0f || cos_u < 0.0f || cos_theta_plus_u < cos_e * cos_o + sin_e * sin_o)
    return r;
  const float cos_max_outgoing = cos_theta_plus_u * cos_o - sin_from_cos(cos_theta_plus_u) * sin_o;
  r.min = std::abs(cos_max_incidence * b.power * cos_max_outgoing / (e.max_distance * e.max_distance));
  return r;
}

class CyclesImportance : public NodeImportance {
 public:
  explicit CyclesImportance(const Emitters& emitters) : emitters_(emitters) {}

  /// Cycles' get_left_probability: the mean of the first child's share of the upper bounds and
  /// its share of the lower bounds (when both lower bounds are zero, of the children that may
  /// bring anything).
  std::optional<float> first_child_probability(const LightTreeNode& first, const LightTreeNode& second,
                                               const ShadingPoint& at) const override {
    const ImportanceRange a = range(first, at), b = range(second, at);
    const float total_max = a.max + b.max;
    if (!(total_max > 0.0f)) return std::nullopt;
    const float total_min = a.min + b.min;
    const float share_of_min = total_min > 0.0f ? a.min / total_min
                                                : 0.5f * (float(a.max > 0.0f) + float(b.max == 0.0f));
    return 0.5f * (a.max / total_max + share_of_min);
  }

 private:
  ImportanceRange range(const LightTreeNode& node, const ShadingPoint& at) const {
    // A punctual light is its box, a point.
    if (!node.leaf || node.index >= emitters_.count())
      return cycles_range(node.bounds, box_extent(node.bounds, at.position), at.normal);
    const Extent e = triangle_extent(emitters_.vertices(node.index), node.bounds, at.position);
    // A one-sided triangle lights nothing behind its plane.
    const bool front_facing = node.bounds.cos_theta_o < 1.0f || glm::dot(node.bounds.axis, e.to_centre) < 0.0f;
    return front_facing ? cycles_range(node.bounds, e, at.normal) : ImportanceRange{};
  }

  const Emitters& emitters_;
};

}  // namespace

float pbrt_importance(const LightBounds& b, const ShadingPoint& at) {
  const glm::vec3 from_centre = at.position - b.centre();
  const float d2 = glm::dot(from_centre, from_centre);
  // pbrt-v4 clamps d^2 below by |diagonal| / 2, a length against a squared length, which
  // depends on the scene's units. Clamped here by (|diagonal| / 2)^2, the squared radius of the
  // box's bounding sphere: outside the sphere d^2 exceeds it anyway, and inside it every
  // direction may reach a light, so only the power and the clamped distance count.
  const float r2 = b.radius * b.radius;
  if (d2 < r2) return b.power / r2;

  const float inverse_d = 1.0f / std::sqrt(d2);
  const glm::vec3 wi = from_centre * inverse_d;
  // theta_b: the angle the bounding sphere subtends at the point.
  const float sin_b = b.radius * inverse_d, cos_b = sin_from_cos(sin_b);
  // theta': the angle between the point and the nearest direction any light may emit along.
  const float cos_w = glm::dot(b.axis, wi), sin_w = sin_from_cos(cos_w);
  const float cos_x = cos_minus_clamped(sin_w, cos_w, b.sin_theta_o, b.cos_theta_o);
  const float sin_x = sin_minus_clamped(sin_w, cos_w, b.sin_theta_o, b.cos_theta_o);
  const float cos_emitted = cos_minus_clamped(sin_x, cos_x, sin_b, cos_b);
  if (cos_emitted <= b.cos_theta_e) return 0.0f;
  // theta'_i: incidence at the point, widened by theta_b.
  const float cos_i = std::abs(glm::dot(wi, at.normal)), sin_i = sin_from_cos(cos_i);
  const float cos_incident = cos_minus_clamped(sin_i, cos_i, sin_b, cos_b);
  return std::max(b.power * cos_emitted / d2 * cos_incident, 0.0f);
}

std::unique_ptr<NodeImportance> make_node_importance(TreeImportance kind, const Emitters& emitters) {
  if (kind == TreeImportance::cycles) return std::make_unique<CyclesImportance>(emitters);
  return std::make_unique<PbrtImportance>();
}

}  // namespace tracer
