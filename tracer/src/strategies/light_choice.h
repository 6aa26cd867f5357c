#pragma once
// Which light a next-event query draws from, and with what probability (pbrt-v4's
// LightSampler): in proportion to a weight per light (its area or its power), or by a walk
// down the light tree from the shading point. Lights are numbered as the emitters number their
// triangles, then the punctual lights after them (Emitters::count() + i): the tree holds point
// and spot lights as leaves beside the triangles and chooses directional lights apart, as
// pbrt-v4's BVHLightSampler chooses its infinite lights.

#include <cstdint>
#include <memory>
#include <optional>

#include "tracer/light_strategy.h"

namespace tracer {

class NodeImportance;

/// The emissive triangles as one light: what a choice for a point draw that picks the triangle
/// itself gives (make_grouped_power_choice).
inline constexpr std::uint32_t kEveryTriangle = 0xffffffffu;

struct LightPick {
  std::uint32_t light;  ///< a light, or kEveryTriangle
  double pmf;
};

class LightChoice {
 public:
  virtual ~LightChoice() = default;
  /// The first of a query's random words that the point on the light reads: the choice reads
  /// those before it (make_grouped_power_choice reads words 6 and 7, which no point reads).
  virtual int first_point_word() const = 0;
  /// A light for `at`; none when no light can reach it.
  virtual std::optional<LightPick> pick(const LightRandom& random, const ShadingPoint& at) const = 0;
  /// The probability that pick() gives `light` for `at` (for a triangle, that of kEveryTriangle
  /// where the choice groups them).
  virtual double pmf(std::uint32_t light, const ShadingPoint& at) const = 0;
  /// The emission changed: the weights follow.
  virtual void emission_changed() {}
  virtual StrategySetup setup() const { return {}; }
};

/// Each triangle in proportion to its area (`uniform`); beside punctual lights, the triangles as a
/// whole and each punctual light by power (Emitters::power), the triangles' share by area.
std::unique_ptr<LightChoice> make_area_choice(const Emitters& emitters);
/// Each light, punctual ones included, in proportion to its power (`power`; pbrt-v4's
/// PowerLightSampler).
std::unique_ptr<LightChoice> make_power_choice(const Emitters& emitters);
/// The emissive triangles as one light (kEveryTriangle; none where `triangles` is false) beside
/// each punctual light, by power (Emitters::power): for strategies whose point draw picks the
/// triangle itself (trs, texel, plugins).
std::unique_ptr<LightChoice> make_grouped_power_choice(const Emitters& emitters, bool triangles);
/// The light tree over the triangles and the punctual lights, its walk weighing a node's children
/// with `importance`.
std::unique_ptr<LightChoice> make_tree_choice(const Emitters& emitters, TreePower power,
                                              std::unique_ptr<const NodeImportance> importance);

}  // namespace tracer
