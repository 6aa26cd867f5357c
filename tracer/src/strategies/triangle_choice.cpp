#include "strategies/triangle_choice.h"

#include <algorithm>
#include <stdexcept>

#include <lightsampler/random.h>
#include <lightsampler/triangle_map.h>

namespace tracer {

TriangleChoice::TriangleChoice(const Emitters& emitters, std::span<const double> weights) : emitters_(emitters) {
  set_weights(weights);
}

void TriangleChoice::set_weights(std::span<const double> weights) {
  cdf_.assign(weights.size(), 0.0);
  area_density_.assign(weights.size(), 0.0f);
  double total = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) cdf_[i] = total += weights[i];
  if (!(total > 0.0)) {  // the lights emit nothing (a dark frame): nothing to sample
    cdf_.clear();
    return;
  }
  for (std::size_t i = 0; i < weights.size(); ++i) {
    cdf_[i] /= total;
    const float area = emitters_.area(std::uint32_t(i));
    if (area > 0.0f) area_density_[i] = float(weights[i] / total / area);
  }
  cdf_.back() = 1.0;
}

std::optional<LightSample> TriangleChoice::sample(const LightRandom& random,
                                                  const ShadingPoint&) const {
  const double u = lightsampler::uniform_double(random[0]);
  // The first light whose CDF exceeds u: zero-weight lights are never chosen.
  const auto light = std::uint32_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
  // Past the end: no light (an empty CDF), or u at the last rounding of the total.
  if (light >= cdf_.size() || area_density_[light] == 0.0f) return std::nullopt;
  const lightsampler::Barycentrics b = lightsampler::triangle_map(
      lightsampler::uniform_float(random[1]), lightsampler::uniform_float(random[2]));
  const float density = area_density_[light];
  return light_point(emitters_, light, b.b1, b.b2, density, density);
}

float TriangleChoice::pdf(std::uint32_t light, float, float, const ShadingPoint&) const {
  return area_density_[light];
}

}  // namespace tracer
