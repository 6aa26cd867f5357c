// `cosine-power`: a light strategy in one file, built outside the tree against the installed
// tracer and loaded with `trs-render --plugin`. It chooses an emissive triangle in proportion to
// its emitted power times how squarely it faces the shading point, then a uniform point on it.
//
// Light i weighs w_i = P_i max(cos_i, floor): P_i its power (Light::power, watts of
// luminance), cos_i the cosine between the shading normal and the direction to its centroid. The
// floor keeps every light that emits drawable, so the estimate stays unbiased where a light whose
// centroid is below the horizon still reaches the point (a large triangle, a transmissive
// surface). Its density on the lights is w_i / sum(w) over the triangle's area, and pdf() computes
// it again from the shading point, so that a BSDF hit is weighed exactly as the light sample that
// could have found it. Each draw weighs every light: for scenes of a few thousand emitters.

#include <tracer/strategy_registry.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

class CosinePower : public tracer::LightStrategy {
 public:
  CosinePower(const tracer::Emitters& emitters, double floor) : emitters_(emitters), floor_(floor) {
    for (std::uint32_t light = 0; light < emitters.count(); ++light) {
      const auto v = emitters.vertices(light);
      centroids_.push_back((v[0] + v[1] + v[2]) / 3.0f);
    }
  }

  std::string name() const override { return "cosine-power"; }

  std::optional<tracer::LightLiSample> sample(const tracer::LightRandom& random,
                                              const tracer::ShadingPoint& at) const override {
    const std::vector<double> cumulative = cumulative_weights(at);
    const double total = cumulative.back();
    if (!(total > 0.0)) return std::nullopt;  // nothing emits
    const double u = tracer::uniform53(random, 0) * total;
    const auto light = std::uint32_t(std::min<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin(), cumulative.size() - 1));
    // A uniform point on the triangle: b1 weighs its second corner, b2 its third.
    const float r = std::sqrt(uniform(random[2])), s = uniform(random[3]);
    const float b1 = r * (1.0f - s), b2 = r * s;
    const float density = this->density(light, cumulative);
    if (!(density > 0.0f)) return std::nullopt;
    // The light turns its point into what the shading point sees, in solid angle.
    const tracer::Light chosen = emitters_.light(light);
    return chosen.sample_li(chosen.point(b1, b2, density, density), at);
  }

  float pdf(std::uint32_t light, float, float, const tracer::ShadingPoint& from) const override {
    return density(light, cumulative_weights(from));
  }

 private:
  /// The area density of a point of `light`, from the lights' weights summed in light order.
  float density(std::uint32_t light, const std::vector<double>& cumulative) const {
    const double total = cumulative.back();
    if (!(total > 0.0)) return 0.0f;
    const double weight = cumulative[light] - (light > 0 ? cumulative[light - 1] : 0.0);
    return float(weight / total / double(emitters_.area(light)));
  }

  static float uniform(std::uint32_t word) { return float(word >> 8) * 0x1p-24f; }

  /// The lights' weights seen from `at`, summed in light order.
  std::vector<double> cumulative_weights(const tracer::ShadingPoint& at) const {
    std::vector<double> cumulative(emitters_.count());
    double sum = 0.0;
    for (std::uint32_t light = 0; light < emitters_.count(); ++light) {
      const glm::vec3 to = centroids_[light] - at.position;
      const float length = glm::length(to);
      const double cosine = length > 0.0f ? double(glm::dot(at.normal, to / length)) : 1.0;
      sum += emitters_.light(light).power() * std::max(cosine, floor_);
      cumulative[light] = sum;
    }
    return cumulative;
  }

  const tracer::Emitters& emitters_;
  double floor_;
  std::vector<glm::vec3> centroids_;
};

/// --strategy-option floor=VALUE, in (0, 1]; 0.1 without it.
double floor_option(const tracer::StrategyOptions& options) {
  const auto given = options.parameters.find("floor");
  if (given == options.parameters.end()) return 0.1;
  std::size_t used = 0;
  double floor = 0.0;
  try {
    floor = std::stod(given->second, &used);
  } catch (const std::exception&) {
  }
  if (used != given->second.size() || !(floor > 0.0 && floor <= 1.0))
    throw std::invalid_argument("cosine-power: floor takes a number in (0, 1], not " + given->second);
  return floor;
}

TRS_REGISTER_STRATEGY({.name = "cosine-power",
                       .summary = "triangles by power times the cosine towards them, floored",
                       .make = [](const tracer::StrategyContext& c) {
                         return std::make_unique<CosinePower>(c.emitters, floor_option(c.options));
                       },
                       .parameters = {{"floor", "the least cosine a light is weighed with, in (0, 1]; 0.1"}}});

}  // namespace
