#pragma once
// How next-event estimation picks a point on the lights. One interface; each strategy is one
// small file in src/strategies/.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <lightsampler/sampler.h>

#include "tracer/emitters.h"

namespace tracer {

struct LightSample {
  std::uint32_t light;
  float b1;
  float b2;
  glm::vec3 position;
  /// Area density (per world area) the estimator divides by.
  float pdf;
  /// Area density at this point as pdf() gives it, for MIS weights. Equal to `pdf` except for
  /// point-light sets, whose estimator carries the set's size (see TrsStrategy).
  float mis_pdf;
};

struct LightFrame {
  double sampler_ms = 0.0;     ///< light-sampler time, milliseconds
  std::uint64_t lights = 0;    ///< point lights drawn
  std::uint64_t candidates = 0;  ///< points the rejection loops tried
  std::uint64_t exhausted = 0; ///< lights that reached the sampler's rejection limit (biased)
  std::vector<lightsampler::PassTime> passes;  ///< the sampler's time per pass
};

class LightStrategy {
 public:
  virtual ~LightStrategy() = default;

  virtual std::string name() const = 0;
  /// Called before each frame's paths; `frame` numbers frames from 0.
  virtual void begin_frame(std::uint64_t frame) { (void)frame; }
  /// A point on the lights from three independent uniform 32-bit words; none when the
  /// lights have nothing to offer this frame.
  virtual std::optional<LightSample> sample(const std::array<std::uint32_t, 3>& random) const = 0;
  /// Area density with which sample() picks a point of a light; what a BSDF-sampled hit on the
  /// light weighs against.
  virtual float pdf(std::uint32_t light, float b1, float b2) const = 0;

  /// What the light sampler did in the last frame (zeros for strategies without one).
  virtual LightFrame last_frame() const { return {}; }
  /// The sampler's backend and device, for reports; empty for strategies without one.
  virtual std::string device() const { return {}; }
};

enum class StrategyKind { uniform, power, trs };

struct StrategyOptions {
  StrategyKind kind = StrategyKind::trs;
  double lights = 1e6;          ///< trs: expected point lights per frame (N_target)
  std::uint64_t seed = 0;       ///< trs: frame f draws its set with a seed from (seed, f)
};

/// Throws std::invalid_argument when the scene has no lights.
std::unique_ptr<LightStrategy> make_light_strategy(const Emitters& emitters,
                                                   const StrategyOptions& options);

const char* to_string(StrategyKind kind);
std::optional<StrategyKind> parse_strategy(const std::string& name);

}  // namespace tracer
