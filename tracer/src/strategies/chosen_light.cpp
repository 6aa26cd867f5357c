// The strategies that choose a light for the shading point and then a point on it: a light
// choice (light_choice.h) times a way to draw a point on a triangle (triangle_point.h). Every
// choice holds the punctual lights too; a punctual light chosen gives its delta sample.
// - `uniform`: a triangle by its area, a uniform point on it: blind to the emission.
// - `power`: a light by its emitted power (Emitters::power: a triangle's integrated over its
//   texels by the counting pass), a uniform point on it: what production renderers do, right
//   between triangles, blind to the texture within one.
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
#include "tracer/strategy_registry.h"

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

  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    const std::optional<LightPick> pick = choice_->pick(random, at);
    if (!pick) return std::nullopt;
    if (pick->light >= emitters_.count()) return punctual_sample(emitters_, pick->light - emitters_.count(), pick->pmf, at);
    const std::optional<PointOnLight> p = point_->sample(pick->light, random, choice_->words(), at);
    if (!p) return std::nullopt;
    // A point seen edge-on, or in a texel without density, carries nothing; pdf() gives it zero too.
    const auto density = float(pick->pmf * p->density);
    if (!(density > 0.0f)) return std::nullopt;
    return seen_from(emitters_, light_point(emitters_, pick->light, p->b.b1, p->b.b2, density, density), at);
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

namespace {

std::unique_ptr<LightChoice> tree_choice(const StrategyContext& c) {
  const TreeOptions& tree = c.options.tree;
  return make_tree_choice(c.emitters, tree.power, make_node_importance(tree.importance, c.emitters));
}

TRS_REGISTER_STRATEGY({.name = "uniform",
                       .summary = "triangles by area",
                       .make = [](const StrategyContext& c) {
                         return make_chosen_light_strategy(c.emitters, make_area_choice(c.emitters),
                                                           make_area_point(c.emitters), "uniform");
                       },
                       .draws_punctual_lights = true});
TRS_REGISTER_STRATEGY({.name = "power",
                       .summary = "lights by emitted power",
                       .make = [](const StrategyContext& c) {
                         return make_chosen_light_strategy(c.emitters, make_power_choice(c.emitters),
                                                           make_area_point(c.emitters), "power");
                       },
                       .draws_punctual_lights = true});
TRS_REGISTER_STRATEGY({.name = "tree",
                       .summary = "a light tree that weighs the lights for each shading point",
                       .make = [](const StrategyContext& c) {
                         return make_chosen_light_strategy(c.emitters, tree_choice(c),
                                                           make_solid_angle_point(c.emitters), "tree");
                       },
                       .picks_by_tree = true,
                       .draws_punctual_lights = true});
TRS_REGISTER_STRATEGY({.name = "tree-texel",
                       .summary = "the light tree's triangle, then a texel piece of it",
                       .make = [](const StrategyContext& c) {
                         return make_chosen_light_strategy(c.emitters, tree_choice(c),
                                                           make_texel_point(c.emitters), "tree-texel");
                       },
                       .picks_by_tree = true,
                       .draws_punctual_lights = true});

}  // namespace

}  // namespace tracer
