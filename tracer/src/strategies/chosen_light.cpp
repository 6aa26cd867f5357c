// The strategies that choose a light for the shading point and then a point on it: a light
// choice (light_choice.h) times a way to draw a point on a triangle (triangle_point.h).
// - `uniform`: a triangle by its area, a uniform point on it: blind to the emission.
// - `power`: a triangle by its emitted power, integrated over its texels (the counting pass's
//   N-bar_T, in luminance), a uniform point on it: what production renderers do, right between
//   triangles, blind to the texture within one.
// - `tree`: the light tree's walk from the shading point, a point uniform in the triangle's solid
//   angle where that pays, by area otherwise.
// - `tree-texel`: the tree's walk, a point by the triangle's texels.
// The point's area density is the choice's probability times its density on the light, and pdf()
// computes both again from the shading point, so that a BSDF hit is weighed exactly as the light
// sample that could have found it.

#include "strategies/light_choice.h"
#include "strategies/strategies.h"
#include "strategies/tree_importance.h"
#include "strategies/triangle_point.h"

namespace tracer {
namespace {

class ChosenLight : public LightStrategy {
 public:
  ChosenLight(const Emitters& emitters, std::unique_ptr<LightChoice> choice, std::unique_ptr<TrianglePoint> point,
              std::string name)
      : emitters_(emitters), choice_(std::move(choice)), point_(std::move(point)), name_(std::move(name)) {}

  std::string name() const override { return name_; }

  void emission_changed() override {
    choice_->emission_changed();
    point_->emission_changed();
  }

  std::optional<LightSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    const std::optional<LightPick> pick = choice_->pick(random, at);
    if (!pick) return std::nullopt;
    if (pick->light >= emitters_.count()) return punctual_sample(emitters_, pick->light - emitters_.count(), pick->pmf, at);
    const std::optional<PointOnLight> p = point_->sample(pick->light, random, choice_->words(), at);
    if (!p) return std::nullopt;
    // A point seen edge-on, or in a texel without density, carries nothing; pdf() gives it zero too.
    const auto density = float(pick->pmf * p->density);
    if (!(density > 0.0f)) return std::nullopt;
    return light_point(emitters_, pick->light, p->b.b1, p->b.b2, density, density);
  }

  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    const double pmf = choice_->pmf(light, from);
    if (!(pmf > 0.0)) return 0.0f;
    return float(pmf * point_->density(light, b1, b2, from));
  }

  StrategySetup setup() const override {
    const StrategySetup choice = choice_->setup(), point = point_->setup();
    return {choice.build_ms + point.build_ms, choice.bytes + point.bytes};
  }

 private:
  const Emitters& emitters_;
  std::unique_ptr<LightChoice> choice_;
  std::unique_ptr<TrianglePoint> point_;
  std::string name_;
};

}  // namespace

std::unique_ptr<LightStrategy> make_chosen_light_strategy(const Emitters& emitters, std::unique_ptr<LightChoice> choice,
                                                          std::unique_ptr<TrianglePoint> point, std::string name) {
  return std::make_unique<ChosenLight>(emitters, std::move(choice), std::move(point), std::move(name));
}

std::unique_ptr<LightStrategy> make_chosen_light_strategy(const Emitters& emitters, StrategyKind kind,
                                                          const TreeOptions& tree) {
  const auto tree_choice = [&] {
    return make_tree_choice(emitters, tree.power, make_node_importance(tree.importance, emitters));
  };
  switch (kind) {
    case StrategyKind::uniform:
      return make_chosen_light_strategy(emitters, make_area_choice(emitters), make_area_point(emitters), to_string(kind));
    case StrategyKind::power:
      return make_chosen_light_strategy(emitters, make_power_choice(emitters), make_area_point(emitters), to_string(kind));
    case StrategyKind::tree:
      return make_chosen_light_strategy(emitters, tree_choice(), make_solid_angle_point(emitters), to_string(kind));
    case StrategyKind::tree_texel:
      return make_chosen_light_strategy(emitters, tree_choice(), make_texel_point(emitters), to_string(kind));
    default:
      throw std::invalid_argument(std::string(to_string(kind)) + " does not choose a light and then a point on it");
  }
}

}  // namespace tracer
