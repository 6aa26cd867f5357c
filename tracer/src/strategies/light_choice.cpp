#include "strategies/light_choice.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include <lightsampler/random.h>

#include "strategies/light_tree.h"
#include "strategies/tree_importance.h"
#include "strategies/unit_interval.h"

namespace tracer {
namespace {

/// Lights in proportion to a weight each, from one 32-bit word.
class WeightChoice : public LightChoice {
 public:
  /// `weights(emitters)` per light, numbered as the choices number them, non-negative; all
  /// zero, nothing is picked.
  using Weights = std::vector<double> (*)(const Emitters&);
  WeightChoice(const Emitters& emitters, Weights weights) : emitters_(emitters), weights_(weights) {
    emission_changed();
  }

  int first_point_word() const override { return 1; }

  std::optional<LightPick> pick(const LightRandom& random, const ShadingPoint&) const override {
    const double u = lightsampler::uniform_double(random[0]);
    // The first light whose CDF exceeds u: zero-weight lights are never chosen.
    const auto light = std::uint32_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
    // Past the end: no light (an empty CDF), or u at the last rounding of the total.
    if (light >= cdf_.size() || !(pmf_[light] > 0.0)) return std::nullopt;
    return LightPick{light, pmf_[light]};
  }

  double pmf(std::uint32_t light, const ShadingPoint&) const override {
    return light < pmf_.size() ? pmf_[light] : 0.0;
  }

  void emission_changed() override {
    const std::vector<double> weights = weights_(emitters_);
    cdf_.assign(weights.size(), 0.0);
    pmf_.assign(weights.size(), 0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) cdf_[i] = total += weights[i];
    if (!(total > 0.0)) {  // the lights emit nothing (a dark frame): nothing to pick
      cdf_.clear();
      return;
    }
    for (std::size_t i = 0; i < weights.size(); ++i) {
      cdf_[i] /= total;
      pmf_[i] = weights[i] / total;
    }
    cdf_.back() = 1.0;
  }

 private:
  const Emitters& emitters_;
  Weights weights_;
  std::vector<double> cdf_;  ///< inclusive, normalised to end at 1
  std::vector<double> pmf_;
};

/// The triangles by area. Beside punctual lights, the triangles as a whole weigh their power,
/// shared out by area, and each punctual light its own: the choice between them is by power.
std::vector<double> areas(const Emitters& emitters) {
  const std::uint32_t triangles = emitters.count(), punctual = emitters.punctual().count();
  std::vector<double> w(triangles + punctual);
  double area = 0.0;
  for (std::uint32_t i = 0; i < triangles; ++i) area += w[i] = emitters.area(i);
  if (punctual == 0) return w;
  double power = 0.0;
  for (std::uint32_t i = 0; i < triangles; ++i) power += emitters.power(i);
  for (std::uint32_t i = 0; i < triangles; ++i) w[i] = area > 0.0 ? w[i] * (power / area) : 0.0;
  for (std::uint32_t i = triangles; i < w.size(); ++i) w[i] = emitters.power(i);
  return w;
}

std::vector<double> powers(const Emitters& emitters) {
  std::vector<double> p(emitters.count() + emitters.punctual().count());
  for (std::uint32_t i = 0; i < p.size(); ++i) p[i] = emitters.power(i);
  return p;
}

/// The triangles as one light beside each punctual light, by power: the choice's CDF has the
/// triangles first, [0, triangles_), then each punctual light.
class GroupedPowerChoice : public LightChoice {
 public:
  GroupedPowerChoice(const Emitters& emitters, bool triangles) : emitters_(emitters), any_triangles_(triangles) {
    emission_changed();
  }

  /// Words 6 and 7: no point draw over the triangles reads them.
  int first_point_word() const override { return 0; }

  std::optional<LightPick> pick(const LightRandom& random, const ShadingPoint&) const override {
    const double u = uniform53(random, 6);
    if (u < triangles_) return LightPick{kEveryTriangle, triangles_};
    const auto light = std::uint32_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
    if (light >= cdf_.size()) return std::nullopt;
    const double pmf = punctual_pmf(light);
    if (!(pmf > 0.0)) return std::nullopt;
    return LightPick{emitters_.count() + light, pmf};
  }

  double pmf(std::uint32_t light, const ShadingPoint&) const override {
    return light < emitters_.count() ? triangles_ : punctual_pmf(light - emitters_.count());
  }

  void emission_changed() override {
    double triangles = 0.0;
    if (any_triangles_)
      for (std::uint32_t i = 0; i < emitters_.count(); ++i) triangles += emitters_.power(i);
    const std::uint32_t punctual = emitters_.punctual().count();
    cdf_.assign(punctual, 0.0);
    double total = triangles;
    for (std::uint32_t i = 0; i < punctual; ++i) cdf_[i] = total += emitters_.power(emitters_.count() + i);
    if (!(total > 0.0)) {  // nothing emits (a dark frame): nothing to pick
      triangles_ = 0.0;
      cdf_.assign(punctual, 0.0);
      return;
    }
    triangles_ = triangles / total;
    for (double& c : cdf_) c /= total;
    if (!cdf_.empty()) cdf_.back() = 1.0;
  }

 private:
  double punctual_pmf(std::uint32_t i) const { return cdf_[i] - (i > 0 ? cdf_[i - 1] : triangles_); }

  const Emitters& emitters_;
  bool any_triangles_;
  double triangles_ = 0.0;   ///< the triangles' probability
  std::vector<double> cdf_;  ///< inclusive, per punctual light, after the triangles' share
};

/// The light tree over the triangles and the point and spot lights; directional lights, which
/// no box bounds, each with the tree's probability (pbrt-v4's pInfinite).
class TreeChoice : public LightChoice {
 public:
  TreeChoice(const Emitters& emitters, TreePower power, std::unique_ptr<const NodeImportance> importance)
      : emitters_(emitters), power_(power), importance_(std::move(importance)), tree_(timed_build()) {
    for (std::uint32_t i = 0; i < emitters.punctual().count(); ++i)
      if (emitters.punctual()[i].kind == PunctualLight::Kind::directional) directional_.push_back(i);
  }

  int first_point_word() const override { return 2; }

  std::optional<LightPick> pick(const LightRandom& random, const ShadingPoint& at) const override {
    double u = uniform53(random, 0);
    const double tree_share = tree_probability();
    if (!directional_.empty()) {
      if (u >= tree_share) {
        const auto i = std::min(std::size_t((u - tree_share) / (1.0 - tree_share) * double(directional_.size())),
                                directional_.size() - 1);
        return LightPick{emitters_.count() + directional_[i], directional_probability()};
      }
      u = below_one(u / tree_share);
    }
    const std::optional<LightTree::Pick> p = tree_.sample(u, at, *importance_);
    if (!p) return std::nullopt;
    return LightPick{p->light, tree_share * double(p->pmf)};
  }

  double pmf(std::uint32_t light, const ShadingPoint& at) const override {
    const bool directional = light >= emitters_.count() &&
                             emitters_.punctual()[light - emitters_.count()].kind == PunctualLight::Kind::directional;
    if (directional) return directional_probability();
    return tree_probability() * double(tree_.pmf(light, at, *importance_));
  }

  /// The lights' powers changed: the tree is built again, as a fresh one over them would be (a
  /// refit would keep a topology chosen for the old powers, and a frame would then depend on
  /// the frames before it).
  void emission_changed() override { tree_ = timed_build(); }

  StrategySetup setup() const override { return {build_ms_, tree_.bytes()}; }

 private:
  /// The share of the walk down the tree; the directional lights share the rest evenly.
  double tree_probability() const {
    if (directional_.empty()) return 1.0;
    return tree_.nodes().empty() ? 0.0 : 1.0 / double(directional_.size() + 1);
  }
  double directional_probability() const { return (1.0 - tree_probability()) / double(directional_.size()); }

  LightTree timed_build() {
    const auto start = std::chrono::steady_clock::now();
    LightTree tree(emitters_, tree_power(emitters_, power_));
    build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return tree;
  }

  const Emitters& emitters_;
  TreePower power_;
  std::unique_ptr<const NodeImportance> importance_;
  double build_ms_ = 0.0;
  LightTree tree_;
  std::vector<std::uint32_t> directional_;  ///< the punctual lights that are directional
};

}  // namespace

std::unique_ptr<LightChoice> make_area_choice(const Emitters& emitters) {
  return std::make_unique<WeightChoice>(emitters, areas);
}

std::unique_ptr<LightChoice> make_power_choice(const Emitters& emitters) {
  return std::make_unique<WeightChoice>(emitters, powers);
}

std::unique_ptr<LightChoice> make_grouped_power_choice(const Emitters& emitters, bool triangles) {
  return std::make_unique<GroupedPowerChoice>(emitters, triangles);
}

std::unique_ptr<LightChoice> make_tree_choice(const Emitters& emitters, TreePower power,
                                              std::unique_ptr<const NodeImportance> importance) {
  return std::make_unique<TreeChoice>(emitters, power, std::move(importance));
}

}  // namespace tracer
