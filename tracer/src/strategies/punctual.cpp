// Punctual lights beside the emissive triangles: one choice by power (Emitters::power) between
// the triangles' strategy, as a whole, and each punctual light, as pbrt-v4's PowerLightSampler
// chooses among all its lights, each light's probability multiplying its sample's density. A
// punctual light is a delta light: its sample carries the probability of choosing it and the
// irradiance it brings, and no BSDF sample finds it.

#include <algorithm>

#include <lightsampler/random.h>

#include "strategies/strategies.h"

namespace tracer {
namespace {

class PunctualMixture : public LightStrategy {
 public:
  PunctualMixture(const Emitters& emitters, std::unique_ptr<LightStrategy> area, std::string name)
      : emitters_(emitters), area_(std::move(area)), name_(std::move(name)) {
    set_weights();
  }

  std::string name() const override { return name_; }
  void begin_pass(std::uint64_t seed) override {
    if (area_) area_->begin_pass(seed);
  }
  void emission_changed() override {
    if (area_) area_->emission_changed();
    set_weights();
  }

  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    // Words 6 and 7: no strategy of the triangles reads them.
    const double u = uniform53(random, 6);
    if (u < area_probability_) {
      std::optional<LightLiSample> s = area_->sample(random, at);
      if (s) {
        s->pdf *= float(area_probability_);
        s->mis_pdf *= float(area_probability_);
      }
      return s;
    }
    const auto light = std::uint32_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
    if (light >= cdf_.size()) return std::nullopt;
    const double pmf = cdf_[light] - (light > 0 ? cdf_[light - 1] : area_probability_);
    if (!(pmf > 0.0)) return std::nullopt;
    return punctual_sample(emitters_, light, pmf, at);
  }

  void prefetch(const LightRandom& random) const override {
    if (area_) area_->prefetch(random);
  }

  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return area_ ? float(area_probability_) * area_->pdf(light, b1, b2, from) : 0.0f;
  }

  LightPass last_pass() const override { return area_ ? area_->last_pass() : LightPass{}; }
  std::string device() const override { return area_ ? area_->device() : std::string(); }
  StrategySetup setup() const override { return area_ ? area_->setup() : StrategySetup{}; }

 private:
  /// The choice's CDF: the triangles first, [0, area_probability_), then each punctual light.
  void set_weights() {
    double area = 0.0;
    if (area_)
      for (std::uint32_t i = 0; i < emitters_.count(); ++i) area += emitters_.power(i);
    const std::uint32_t punctual = emitters_.punctual().count();
    cdf_.assign(punctual, 0.0);
    double total = area;
    for (std::uint32_t i = 0; i < punctual; ++i) cdf_[i] = total += emitters_.power(emitters_.count() + i);
    if (!(total > 0.0)) {  // nothing emits (a dark frame): nothing to sample
      area_probability_ = 0.0;
      cdf_.assign(punctual, 0.0);
      return;
    }
    area_probability_ = area / total;
    for (double& c : cdf_) c /= total;
    if (!cdf_.empty()) cdf_.back() = 1.0;
  }

  const Emitters& emitters_;
  std::unique_ptr<LightStrategy> area_;  ///< none where no triangle emits
  std::string name_;
  double area_probability_ = 0.0;
  std::vector<double> cdf_;  ///< inclusive, per punctual light, after the triangles' share
};

}  // namespace

std::optional<LightLiSample> punctual_sample(const Emitters& emitters, std::uint32_t light, double pmf,
                                             const ShadingPoint& at) {
  const PunctualLi li = emitters.punctual().li(light, at.position);
  if (!(li.li.r > 0.0f || li.li.g > 0.0f || li.li.b > 0.0f)) return std::nullopt;
  return LightLiSample{.li = li.li,
                       .wi = li.wi,
                       .distance = li.distance,
                       .pdf = float(pmf),
                       .mis_pdf = 0.0f,
                       .position = emitters.punctual()[light].position,
                       .normal = glm::vec3(0.0f),
                       .light = emitters.count() + light,
                       .delta = true};
}

std::unique_ptr<LightStrategy> with_punctual_lights(const Emitters& emitters, std::unique_ptr<LightStrategy> area,
                                                    std::string name) {
  return std::make_unique<PunctualMixture>(emitters, std::move(area), std::move(name));
}

}  // namespace tracer
