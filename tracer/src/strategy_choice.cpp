// `auto`: the strategy the scene's emission calls for. Drawing a light's point by its texels
// (trs) rather than uniformly over it (power) pays where the emission varies within the lights:
// a neon sign's strokes on two triangles. Where the lights are small against the texture's
// features (an atlas on a dense mesh), both draws are the same, and `power` is the cheapest per
// sample; the light tree, which weighs distance and orientation, renders 1.1 to 1.7 times fewer
// frames than `power` in this renderer and did not repay it at equal time on the real assets
// measured (docs/noise.md, "Real assets, and the default").
//
// The measure: with x drawn from p(x) = D(x) / I and m_T the mean density of x's light, a
// light chosen by power and a point uniform on it has the density m_T / I, and for an
// integrand that follows the emission the second moments of the two draws are in the ratio
// E_p[D(x) / m_T] (Cauchy-Schwarz makes it at least 1). One frame of the light sampler gives it.

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "tracer/light_strategy.h"
#include "tracer/strategy_registry.h"

namespace tracer {
namespace {

/// Points measured; the estimate's relative error is well below a percent for any emission
/// whose texels vary by less than a few hundred times within a light.
constexpr double kGainSamples = 65536;
constexpr std::uint64_t kGainSeed = 0x7e4e1a9a1ull;

double texel_gain(Emitters& emitters) {
  if (emitters.count() == 0) return 1.0;  // punctual lights alone: no texels to draw by
  lightsampler::Frame frame;
  lightsampler::FrameRequest request;
  request.seed = kGainSeed;
  request.target_count = kGainSamples;
  emitters.sampler().generate(request, frame);
  const std::span<const double> integrals = emitters.light_density();
  double sum = 0.0;
  std::uint64_t count = 0;
  for (const lightsampler::Sample& s : frame.samples.span()) {
    const double mean = integrals[s.triangle] / double(emitters.area(s.triangle));
    if (!(mean > 0.0) || !std::isfinite(mean)) continue;
    sum += double(emitters.density(s.triangle, s.b1, s.b2)) / mean;
    ++count;
  }
  return count > 0 ? sum / double(count) : 1.0;
}

}  // namespace

StrategyChoice choose_strategy(Emitters& emitters, const StrategyOptions& options) {
  if (options.kind != kAutoStrategy) return {options, 0.0, {}};
  StrategyChoice choice{options, texel_gain(emitters), {}};
  const bool texture_decides = choice.texel_gain >= kAutoTexelGain;
  choice.options.kind = texture_decides ? "ris" : "power";
  char reason[160];
  if (texture_decides)
    std::snprintf(reason, sizeof reason, "the emission varies within the lights (texel gain %.2f >= %.2f): ris over %s",
                  choice.texel_gain, kAutoTexelGain, options.candidates_from.c_str());
  else
    std::snprintf(reason, sizeof reason, "the emission is nearly flat on each light (texel gain %.2f < %.2f): power",
                  choice.texel_gain, kAutoTexelGain);
  choice.reason = reason;
  return choice;
}

}  // namespace tracer
