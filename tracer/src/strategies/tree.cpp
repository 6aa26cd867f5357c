// `tree`: a light picked for the shading point by a walk down the light tree (light_tree.h),
// then a point on it: uniform in the solid angle the triangle subtends where that is neither
// tiny nor nearly a hemisphere (pbrt-v4's thresholds), uniform by area otherwise. The point's
// area density is the walk's pmf times the point's density on its triangle, and pdf() computes
// both again from the shading point, so that a BSDF hit is weighed exactly as the light sample
// that could have found it.

#include <algorithm>
#include <numbers>

#include <lightsampler/random.h>
#include <lightsampler/triangle_map.h>

#include "strategies/spherical_triangle.h"
#include "strategies/strategies.h"
#include "strategies/tree.h"
#include "strategies/tree_importance.h"

namespace tracer {
namespace {

/// Solid angles, in steradians, between which a triangle is sampled by direction. Below, cos
/// theta_l / d^2 varies too little over the triangle for sampling by direction to pay for its
/// trigonometry: pbrt-v4 starts at 3e-4 sr, which on the shipped scenes costs up to 26% more time
/// per frame for at most 4% less noise (docs/noise.md); from 0.1 sr, a 1 m^2 panel 3 m
/// away, it pays. Above 6.22 sr (pbrt-v4's) the triangle fills nearly the whole hemisphere and
/// Arvo's construction loses precision.
constexpr double kMinSphericalSolidAngle = 0.1;
constexpr double kMaxSphericalSolidAngle = 6.22;

class TreeStrategy : public LightStrategy {
 public:
  TreeStrategy(const Emitters& emitters, TreePower power, std::unique_ptr<const NodeImportance> importance)
      : emitters_(emitters), power_(power), tree_(emitters, tree_power(emitters, power), std::move(importance)) {}

  void emission_changed() override { tree_.update(emitters_, tree_power(emitters_, power_)); }

  std::string name() const override { return "tree"; }

  std::optional<LightSample> sample(const LightRandom& random,
                                    const ShadingPoint& at) const override {
    const std::optional<LightTree::Pick> pick = tree_.pick(uniform53(random, 0), at);
    if (!pick) return std::nullopt;
    const std::array<glm::vec3, 3> v = emitters_.vertices(pick->light);
    const double omega = spherical_solid_angle(v, at.position);
    const float u1 = lightsampler::uniform_float(random[2]), u2 = lightsampler::uniform_float(random[3]);
    const lightsampler::Barycentrics b = by_direction(omega) ? sample_spherical_triangle(v, at.position, u1, u2)
                                                             : lightsampler::triangle_map(u1, u2);
    const float density = pick->pmf * point_density(pick->light, b.b1, b.b2, at, omega);
    // A point seen edge-on carries nothing, and pdf() gives it zero too.
    if (!(density > 0.0f)) return std::nullopt;
    return light_point(emitters_, pick->light, b.b1, b.b2, density, density);
  }

  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    const float pmf = tree_.pmf(light, from);
    if (!(pmf > 0.0f)) return 0.0f;
    return pmf * point_density(light, b1, b2, from, spherical_solid_angle(emitters_.vertices(light), from.position));
  }

  StrategySetup setup() const override { return tree_.setup(); }

 private:
  static bool by_direction(double omega) {
    return omega >= kMinSphericalSolidAngle && omega <= kMaxSphericalSolidAngle;
  }

  /// The triangle's solid angle seen from `p` where it may be sampled by direction, zero where
  /// the solid angle of its bounding sphere (about its centroid) shows that it is too small: most
  /// lights are far, and that test needs no trigonometry.
  static double spherical_solid_angle(const std::array<glm::vec3, 3>& v, const glm::vec3& p) {
    const glm::dvec3 centroid = (glm::dvec3(v[0]) + glm::dvec3(v[1]) + glm::dvec3(v[2])) / 3.0;
    double r2 = 0.0;
    for (const glm::vec3& corner : v) r2 = std::max(r2, glm::dot(glm::dvec3(corner) - centroid, glm::dvec3(corner) - centroid));
    const glm::dvec3 d = centroid - glm::dvec3(p);
    const double d2 = glm::dot(d, d);
    // A sphere of radius r at distance D subtends 2 pi (1 - sqrt(1 - r^2 / D^2)).
    if (d2 > r2 && 2.0 * std::numbers::pi * (1.0 - std::sqrt(1.0 - r2 / d2)) < kMinSphericalSolidAngle) return 0.0;
    return solid_angle(v, p);
  }

  /// Area density of point (b1, b2) of `light` as drawn for `at`, given the light's solid angle
  /// there: uniform by area, or uniform by direction, whose area density is |cos theta_l| / (d^2
  /// omega).
  float point_density(std::uint32_t light, float b1, float b2, const ShadingPoint& at, double omega) const {
    if (!by_direction(omega)) return 1.0f / emitters_.area(light);
    const glm::dvec3 d = glm::dvec3(emitters_.position(light, b1, b2)) - glm::dvec3(at.position);
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0.0)) return 0.0f;
    const double cos_light = std::abs(glm::dot(glm::dvec3(emitters_.normal(light)), d)) / std::sqrt(d2);
    return float(cos_light / (d2 * omega));
  }

  const Emitters& emitters_;
  TreePower power_;
  TreePicker tree_;
};

}  // namespace

std::unique_ptr<LightStrategy> make_tree_strategy(const Emitters& emitters, TreePower power,
                                                  std::unique_ptr<const NodeImportance> importance) {
  return std::make_unique<TreeStrategy>(emitters, power, std::move(importance));
}

std::unique_ptr<LightStrategy> make_tree_strategy(const Emitters& emitters,
                                                  const StrategyOptions& options) {
  return make_tree_strategy(emitters, options.tree.power,
                            make_node_importance(options.tree.importance, emitters));
}

}  // namespace tracer
