// `tree-texel`: the light tree picks the triangle for the shading point, with its exact power,
// distance and orientation (tree.h), and the triangle's texture picks the point: a texel piece of
// it in proportion to density times area (piece_table.h), then a uniform point in the piece. The
// point's area density is pmf_tree(T | x) D(y) / Phi_T, Phi_T the triangle's integral of D.

#include <algorithm>
#include <chrono>

#include <lightsampler/random.h>

#include "strategies/piece_table.h"
#include "strategies/strategies.h"
#include "strategies/tree.h"
#include "strategies/tree_importance.h"

namespace tracer {
namespace {

class TreeTexelStrategy : public LightStrategy {
 public:
  TreeTexelStrategy(const Emitters& emitters, const TreeOptions& options)
      : emitters_(emitters),
        power_(options.power),
        tree_(emitters, tree_power(emitters, options.power), make_node_importance(options.importance, emitters)) {
    build_table();
  }

  std::string name() const override { return "tree-texel"; }

  void emission_changed() override {
    tree_.update(emitters_, tree_power(emitters_, power_));
    build_table();
  }

  std::optional<LightSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    const std::optional<LightTree::Pick> pick = tree_.pick(uniform53(random, 0), at);
    // With image-mean powers the tree may pick a light that emits nothing.
    if (!pick || !(table_->light_weight(pick->light) > 0.0)) return std::nullopt;
    const PieceTable::Pick piece = table_->pick_in_light(pick->light, word64(random, 2));
    const lightsampler::Barycentrics b =
        table_->point(piece.piece, std::min(float(piece.u), 0x1.fffffep-1f), lightsampler::uniform_float(random[4]),
                     lightsampler::uniform_float(random[5]));
    // Rounding can put a point on its cell's edge into the neighbouring texel: its density is
    // what that texel reads, as pdf() gives it; one without density carries nothing.
    const float p = pick->pmf * density_in_light(pick->light, b.b1, b.b2);
    if (!(p > 0.0f)) return std::nullopt;
    return light_point(emitters_, pick->light, b.b1, b.b2, p, p);
  }

  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    if (!(table_->light_weight(light) > 0.0)) return 0.0f;
    const float pmf = tree_.pmf(light, from);
    return pmf > 0.0f ? pmf * density_in_light(light, b1, b2) : 0.0f;
  }

  StrategySetup setup() const override {
    const StrategySetup tree = tree_.setup();
    return {tree.build_ms + table_build_ms_, tree.bytes + table_->bytes()};
  }

 private:
  void build_table() {
    const auto start = std::chrono::steady_clock::now();
    table_.emplace(emitters_);
    table_build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  /// D(y) / Phi_T: the density of a point within its light.
  float density_in_light(std::uint32_t light, float b1, float b2) const {
    return float(double(emitters_.density(light, b1, b2)) / table_->light_weight(light));
  }

  const Emitters& emitters_;
  TreePower power_;
  TreePicker tree_;
  std::optional<PieceTable> table_;
  double table_build_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<LightStrategy> make_tree_texel_strategy(const Emitters& emitters, const StrategyOptions& options) {
  return std::make_unique<TreeTexelStrategy>(emitters, options.tree);
}

}  // namespace tracer
