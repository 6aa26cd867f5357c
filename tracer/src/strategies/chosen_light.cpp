// Every strategy as a light choice (light_choice.h) times a point draw (point_draw.h): a light
// chosen for the shading point, then a point on it. Every choice holds the punctual lights too;
// a punctual light chosen gives its own delta sample (Light::sample_li).
// - `uniform`: a triangle by its area, a uniform point on it: blind to the emission.
// - `power`: a light by its emitted power (Emitters::power: a triangle's integrated over its
//   texels by the counting pass), a uniform point on it: what production renderers do, right
//   between triangles, blind to the texture within one.
// - `tree`: the light tree's walk from the shading point, a point uniform in the triangle's solid
//   angle where that pays, by area otherwise.
// - `tree-texel`: the tree's walk, a point by the triangle's texels.
// - `trs`, `texel` and plugins that draw their points over the triangles themselves: beside
//   punctual lights, the triangles taken as one light by their power, their points drawn by the
//   strategy (with_punctual_lights), as pbrt-v4's PowerLightSampler chooses among all lights.
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
  ChosenLight(const Emitters& emitters, std::unique_ptr<LightChoice> choice, std::unique_ptr<PointDraw> point,
              std::string name)
      : emitters_(emitters), choice_(std::move(choice)), point_(std::move(point)), name_(std::move(name)) {}

  std::string name() const override { return name_; }

  void begin_pass(std::uint64_t seed) override { point_->begin_pass(seed); }

  void emission_changed() override {
    point_->emission_changed();
    choice_->emission_changed();
  }

  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    const std::optional<LightPick> pick = choice_->pick(random, at);
    if (!pick) return std::nullopt;
    if (pick->light != kEveryTriangle && pick->light >= emitters_.count())
      return emitters_.light(pick->light).sample_li(pick->pmf, at);
    return point_->sample(*pick, random, choice_->first_point_word(), at);
  }

  void prefetch(const LightRandom& random) const override { point_->prefetch(random); }

  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    const double pmf = choice_->pmf(light, from);
    if (!(pmf > 0.0)) return 0.0f;
    return point_->pdf(pmf, light, b1, b2, from);
  }

  LightPass last_pass() const override { return point_->last_pass(); }
  std::string device() const override { return point_->device(); }

  StrategySetup setup() const override {
    const StrategySetup choice = choice_->setup(), point = point_->setup();
    return {choice.build_ms + point.build_ms, choice.bytes + point.bytes};
  }

 private:
  const Emitters& emitters_;
  std::unique_ptr<LightChoice> choice_;
  std::unique_ptr<PointDraw> point_;
  std::string name_;
};

/// A strategy over the emissive triangles alone as the point draw of the triangles taken as one
/// light: its sample's densities, and its pdf(), times the probability of that light.
class TrianglesStrategyPoint : public PointDraw {
 public:
  explicit TrianglesStrategyPoint(std::unique_ptr<LightStrategy> triangles) : triangles_(std::move(triangles)) {}

  std::optional<LightLiSample> sample(const LightPick& pick, const LightRandom& random, int,
                                      const ShadingPoint& at) const override {
    std::optional<LightLiSample> s = triangles_->sample(random, at);
    if (s) {
      s->pdf *= float(pick.pmf);
      s->mis_pdf *= float(pick.pmf);
    }
    return s;
  }
  float pdf(double pmf, std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return float(pmf) * triangles_->pdf(light, b1, b2, from);
  }

  void begin_pass(std::uint64_t seed) override { triangles_->begin_pass(seed); }
  void emission_changed() override { triangles_->emission_changed(); }
  void prefetch(const LightRandom& random) const override { triangles_->prefetch(random); }
  LightPass last_pass() const override { return triangles_->last_pass(); }
  std::string device() const override { return triangles_->device(); }
  StrategySetup setup() const override { return triangles_->setup(); }

 private:
  std::unique_ptr<LightStrategy> triangles_;
};

/// No triangle emits: the grouped choice never picks them.
class NoTrianglePoint : public PointDraw {
 public:
  std::optional<LightLiSample> sample(const LightPick&, const LightRandom&, int, const ShadingPoint&) const override {
    return std::nullopt;
  }
  float pdf(double, std::uint32_t, float, float, const ShadingPoint&) const override { return 0.0f; }
};

}  // namespace

std::unique_ptr<LightStrategy> make_chosen_light_strategy(const Emitters& emitters, std::unique_ptr<LightChoice> choice,
                                                          std::unique_ptr<PointDraw> point, std::string name) {
  return std::make_unique<ChosenLight>(emitters, std::move(choice), std::move(point), std::move(name));
}

std::unique_ptr<LightStrategy> with_punctual_lights(const Emitters& emitters, std::unique_ptr<LightStrategy> triangles,
                                                    std::string name) {
  const bool any = triangles != nullptr;
  std::unique_ptr<PointDraw> point;
  if (any)
    point = std::make_unique<TrianglesStrategyPoint>(std::move(triangles));
  else
    point = std::make_unique<NoTrianglePoint>();
  return make_chosen_light_strategy(emitters, make_grouped_power_choice(emitters, any), std::move(point),
                                    std::move(name));
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
