// `trs`: every frame, lightsampler draws a fresh set of point lights with density proportional
// to the emitted luminance (Triangle Rejection Sampling), and a shading point connects to one
// of them, chosen uniformly.
//
// The estimator: a set of N lights drawn with intensity N_target p(x) (p = D / integral of D)
// and one of them picked uniformly gives E[N / N_target * f(x) / p(x)] = integral of f, exactly,
// N = 0 included. So the density it divides by is p(x) N_target / N, while MIS weighs with p(x),
// the density the set has in expectation.

#include <stdexcept>
#include <string>

#include <lightsampler/random.h>

#include "strategies/strategies.h"

namespace tracer {
namespace {

class TrsStrategy : public LightStrategy {
 public:
  TrsStrategy(const Emitters& emitters, const StrategyOptions& options)
      : emitters_(emitters),
        sampler_(emitters.sampler()),
        target_(options.lights),
        seed_(options.seed) {
    if (!(emitters.total_density() > 0.0))
      throw std::invalid_argument("the lights emit nothing: no density to sample");
    // Picking one light of the set takes 32 random bits.
    if (!(target_ >= 1.0 && target_ < 0x1p32))
      throw std::invalid_argument("trs takes 1 to 2^32 - 1 lights per frame");
  }

  std::string name() const override { return "trs"; }

  void begin_frame(std::uint64_t frame) override {
    const std::uint64_t seed = lightsampler::mix64(seed_ ^ lightsampler::mix64(frame));
    lightsampler::FrameRequest request;
    request.seed = seed;
    request.target_count = target_;
    sampler_.generate(request, frame_);
    if (frame_.sample_count >= 0x1p32)
      throw std::runtime_error("the light sampler drew 2^32 lights or more in one frame");
    scale_ = frame_.sample_count > 0 ? float(target_ / double(frame_.sample_count)) : 0.0f;
  }

  std::optional<LightSample> sample(const std::array<std::uint32_t, 3>& random) const override {
    const std::uint64_t n = frame_.sample_count;
    if (n == 0) return std::nullopt;
    // Lemire's multiply-shift: uniform over n < 2^32 with a bias below n / 2^32.
    const std::uint64_t index = (std::uint64_t(random[0]) * n) >> 32;
    const lightsampler::Sample& s = frame_.samples.span()[index];
    const float p = pdf(s.triangle, s.b1, s.b2);
    // A refined sampler's light, brought back to its triangle, can land an ulp across a texel
    // edge onto a texel without density; it carries nothing.
    if (!(p > 0.0f)) return std::nullopt;
    return LightSample{s.triangle, s.b1, s.b2, emitters_.position(s.triangle, s.b1, s.b2),
                       p * scale_, p};
  }

  float pdf(std::uint32_t light, float b1, float b2) const override {
    return float(double(emitters_.density(light, b1, b2)) / emitters_.total_density());
  }

  LightFrame last_frame() const override {
    return {frame_.total_ms, frame_.sample_count, frame_.candidates, frame_.exhausted, frame_.passes};
  }
  std::string device() const override { return std::string(lightsampler::to_string(sampler_.backend())) + ": " + sampler_.device(); }

 private:
  const Emitters& emitters_;
  lightsampler::Sampler& sampler_;
  double target_;
  std::uint64_t seed_;
  lightsampler::Frame frame_;
  float scale_ = 0.0f;  ///< N_target / N
};

}  // namespace

std::unique_ptr<LightStrategy> make_trs_strategy(const Emitters& emitters,
                                                 const StrategyOptions& options) {
  return std::make_unique<TrsStrategy>(emitters, options);
}

}  // namespace tracer
