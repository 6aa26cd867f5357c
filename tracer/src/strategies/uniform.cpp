// `uniform`: a light chosen in proportion to its area, a uniform point on it. Blind to the
// emissive texture: a dark texel is sampled as often as a bright one.

#include "strategies/strategies.h"
#include "strategies/triangle_choice.h"

namespace tracer {
namespace {

class UniformStrategy : public TriangleChoice {
 public:
  UniformStrategy(const Emitters& emitters, std::vector<double> areas)
      : TriangleChoice(emitters, areas) {}
  std::string name() const override { return "uniform"; }
};

}  // namespace

std::unique_ptr<LightStrategy> make_uniform_strategy(const Emitters& emitters) {
  std::vector<double> areas(emitters.count());
  for (std::uint32_t i = 0; i < emitters.count(); ++i) areas[i] = emitters.area(i);
  return std::make_unique<UniformStrategy>(emitters, std::move(areas));
}

}  // namespace tracer
