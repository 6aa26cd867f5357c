#pragma once
// How a strategy draws the point on the light its choice picked (light_choice.h): on the triangle
// picked (triangle_point.h: by area, by solid angle, by texels), or, where the choice took the
// emissive triangles as one light (kEveryTriangle), anywhere on them, the draw choosing the
// triangle too (trs's point lights, texel's pieces, a plugin's own points).

#include <cstdint>
#include <optional>
#include <string>

#include "strategies/light_choice.h"
#include "tracer/light_strategy.h"

namespace tracer {

class PointDraw {
 public:
  virtual ~PointDraw() = default;
  /// A point of the triangle `pick` names (of any triangle for kEveryTriangle) seen from `at`,
  /// read from the words of `random` from `first` on (the choice reads those before); its
  /// densities are the point's times the pick's probability. None where the light offers nothing
  /// there.
  virtual std::optional<LightLiSample> sample(const LightPick& pick, const LightRandom& random, int first,
                                              const ShadingPoint& at) const = 0;
  /// The area density with which sample() draws point (b1, b2) of triangle `light` from `from`,
  /// its light picked with probability `pmf` (positive).
  virtual float pdf(double pmf, std::uint32_t light, float b1, float b2, const ShadingPoint& from) const = 0;

  // As LightStrategy's.
  virtual void begin_pass(std::uint64_t seed) { (void)seed; }
  virtual void emission_changed() {}
  virtual void prefetch(const LightRandom& random) const { (void)random; }
  virtual LightPass last_pass() const { return {}; }
  virtual std::string device() const { return {}; }
  virtual StrategySetup setup() const { return {}; }
};

}  // namespace tracer
