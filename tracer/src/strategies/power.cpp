// `power`: a light chosen in proportion to the power it emits, integrated over its texels (the
// counting pass's N-bar_T, in luminance), then a uniform point on it. What production renderers
// do: right between triangles, blind to the texture within one.

#include "strategies/strategies.h"
#include "strategies/triangle_choice.h"

namespace tracer {
namespace {

class PowerStrategy : public TriangleChoice {
 public:
  explicit PowerStrategy(const Emitters& emitters)
      : TriangleChoice(emitters, emitters.light_density()) {}
  std::string name() const override { return "power"; }
  void emission_changed() override { set_weights(emitters().light_density()); }
};

}  // namespace

std::unique_ptr<LightStrategy> make_power_strategy(const Emitters& emitters) {
  return std::make_unique<PowerStrategy>(emitters);
}

}  // namespace tracer
