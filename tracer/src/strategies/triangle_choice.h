#pragma once
// A light chosen in proportion to a per-light weight, then a uniform point on it: the usual
// light sampling of renderers, with area or power as the weight.

#include <span>
#include <vector>

#include "tracer/light_strategy.h"

namespace tracer {

class TriangleChoice : public LightStrategy {
 public:
  /// `weights` per light, non-negative; all zero, nothing is sampled.
  TriangleChoice(const Emitters& emitters, std::span<const double> weights);

  std::optional<LightSample> sample(const LightRandom& random,
                                    const ShadingPoint& at) const override;
  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override;

 protected:
  void set_weights(std::span<const double> weights);
  const Emitters& emitters() const { return emitters_; }

 private:
  const Emitters& emitters_;
  std::vector<double> cdf_;          ///< inclusive, normalised to end at 1
  std::vector<float> area_density_;  ///< per light: probability / area
};

}  // namespace tracer
