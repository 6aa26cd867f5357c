// The exact texel-proportional draws of `texel` and `tree-texel`: the alias table, the scene's
// table of texel pieces, and the points drawn from it.
//
// Statistical checks are chi-square tests at alpha 0.01 each (five in this file: family alpha
// about 0.05), fixed seeds; each is shown to reject a deliberately wrong draw.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

#include <lightsampler/random.h>
#include <lightsampler/texel_pieces.h>

#include "scene_builder.h"
#include "strategies/alias_table.h"
#include "strategies/piece_table.h"
#include "tracer/emitters.h"
#include "tracer/light_strategy.h"

namespace {

using namespace tracer;

/// Whether counts over cells follow the expected probabilities: chi-square below its 0.99
/// quantile (Wilson-Hilferty), cells expecting fewer than 5 draws pooled.
bool follows(const std::vector<double>& observed, const std::vector<double>& probability, double draws) {
  double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
  int dof = -1;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    const double e = probability[i] * draws;
    if (e < 5.0) {
      pooled_o += observed[i];
      pooled_e += e;
      continue;
    }
    chi2 += (observed[i] - e) * (observed[i] - e) / e;
    ++dof;
  }
  if (pooled_e > 0.0) {
    chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / std::max(pooled_e, 1e-9);
    ++dof;
  }
  if (dof < 1) return false;
  const double h = 2.0 / (9.0 * dof);
  return chi2 < dof * std::pow(1.0 - h + 2.326 * std::sqrt(h), 3.0);
}

TEST(Alias, GivesEachIndexItsShare) {
  std::mt19937_64 rng(1);
  std::vector<double> weights(57);
  for (std::size_t i = 0; i < weights.size(); ++i) weights[i] = i % 7 == 3 ? 0.0 : std::exp(3.0 * std::sin(double(i)));
  double total = 0.0;
  for (double w : weights) total += w;
  std::vector<alias::Column> columns(weights.size());
  alias::build(weights, columns);
  const alias::Table table(weights);
  std::vector<double> probability(weights.size());
  for (std::size_t i = 0; i < weights.size(); ++i) {
    probability[i] = weights[i] / total;
    // Thresholds are floats: each share to float rounding.
    EXPECT_NEAR(alias::probability(columns, i), probability[i], 1e-7 * probability[i] + 1e-12) << i;
  }
  constexpr int kDraws = 1000000;
  std::vector<double> observed(weights.size(), 0.0), leftover(20, 0.0);
  for (int k = 0; k < kDraws; ++k) {
    const alias::Pick pick = table.sample(rng());
    observed[pick.index] += 1.0;
    ASSERT_LT(pick.u, 1.0);
    leftover[std::size_t(pick.u * 20.0)] += 1.0;
  }
  for (std::size_t i = 0; i < weights.size(); ++i)
    if (weights[i] == 0.0) EXPECT_EQ(observed[i], 0.0) << i;
  EXPECT_TRUE(follows(observed, probability, kDraws));
  // What the choice leaves of the word is uniform: it draws the point in the piece.
  EXPECT_TRUE(follows(leftover, std::vector<double>(20, 0.05), kDraws));
  // The check rejects a table of other weights.
  std::vector<double> skewed = weights;
  skewed[8] *= 1.05;  // the heaviest index, 5% heavier
  std::vector<double> wrong(weights.size(), 0.0);
  const alias::Table other(skewed);
  for (int k = 0; k < kDraws; ++k) wrong[other.sample(rng()).index] += 1.0;
  EXPECT_FALSE(follows(wrong, probability, kDraws));
  EXPECT_THROW(alias::Table(std::vector<double>{0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(alias::Table(std::vector<double>{1.0, -1.0}), std::invalid_argument);
}

/// Three textured quads, one lit only in a few texels, of different strengths and sizes.
struct TexturedQuads {
  Scene scene;
  std::unique_ptr<Emitters> emitters;

  TexturedQuads() {
    Material a;
    a.emissive_factor = glm::vec3(1.0f);
    a.emissive_texture.texture = trs_test::add_random_texture(scene, 6, 5, 0.3, 31);
    Material b = a;
    b.emissive_texture.texture = trs_test::add_random_texture(scene, 7, 4, 0.8, 32);
    b.emissive_strength = 3.0f;
    const std::uint32_t ma = trs_test::add_material(scene, a), mb = trs_test::add_material(scene, b);
    trs_test::add_quad(scene, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, ma);
    trs_test::add_quad(scene, {2, 0, 0}, {2, 0, 1}, {2, 2, 1.5f}, {2, 2, 0}, mb);
    trs_test::add_quad(scene, {0, 3, 0}, {0.5f, 3, 0}, {0.5f, 3.2f, 0}, {0, 3.2f, 0}, ma);
    emitters = std::make_unique<Emitters>(scene, trs_test::kCpuSampler);
  }
};

// Each light's pieces integrate its density as the light sampler's counting pass does.
TEST(PieceTable, WeighsEachLightAsTheCountingPass) {
  const TexturedQuads quads;
  const PieceTable table(*quads.emitters);
  double total = 0.0;
  for (std::uint32_t l = 0; l < quads.emitters->count(); ++l) {
    EXPECT_NEAR(table.light_weight(l), quads.emitters->light_density()[l], 1e-6 * quads.emitters->light_density()[l]) << l;
    total += table.light_weight(l);
  }
  EXPECT_NEAR(table.total_weight(), total, 1e-9 * total);
  EXPECT_NEAR(table.total_weight(), quads.emitters->total_density(), 1e-6 * total);
}

/// The expected share of each (light, texel) cell: density times area over the integral, from
/// the library's pieces.
std::map<std::array<std::uint32_t, 3>, double> texel_shares(const Emitters& emitters, double total) {
  std::map<std::array<std::uint32_t, 3>, double> shares;
  std::vector<lightsampler::TexelPiece> pieces;
  for (std::uint32_t l = 0; l < emitters.count(); ++l) {
    emitters.sampler().maps().texel_pieces(l, pieces);
    for (const auto& p : pieces)
      shares[{l, p.texel.x, p.texel.y}] += double(p.density) * p.area * emitters.area(l) / total;
  }
  return shares;
}

/// Counts of `draws` points of a strategy over the (light, texel) cells of `shares`, in its order.
std::vector<double> counts(const LightStrategy& strategy, const Emitters& emitters,
                           const std::map<std::array<std::uint32_t, 3>, double>& shares, int draws,
                           std::uint64_t seed) {
  std::map<std::array<std::uint32_t, 3>, double> observed;
  std::mt19937 rng(seed);
  const ShadingPoint at{glm::vec3(0.5f, 0.5f, 2.0f), glm::vec3(0, 0, -1)};
  for (int k = 0; k < draws; ++k) {
    LightRandom random;
    for (auto& word : random) word = std::uint32_t(rng());
    const auto s = strategy.sample(random, at);
    if (!s) continue;
    const auto texel = emitters.sampler().maps().texel(s->light, s->b1, s->b2);
    observed[{s->light, texel->x, texel->y}] += 1.0;
  }
  std::vector<double> out;
  for (const auto& [cell, share] : shares) out.push_back(observed[cell]);
  return out;
}

// `texel` draws each (light, texel) cell in proportion to its density times its area, which
// `uniform` (by area alone) does not.
TEST(TexelStrategy, DrawsEachTexelByItsDensityTimesArea) {
  const TexturedQuads quads;
  Emitters& emitters = *quads.emitters;
  const auto shares = texel_shares(emitters, emitters.total_density());
  std::vector<double> probability;
  for (const auto& [cell, share] : shares) probability.push_back(share);
  constexpr int kDraws = 400000;
  for (const std::string& kind : {"texel", "uniform"}) {
    StrategyOptions o;
    o.kind = kind;
    const auto strategy = make_light_strategy(emitters, o);
    EXPECT_EQ(follows(counts(*strategy, emitters, shares, kDraws, 7), probability, kDraws), kind == "texel")
        << kind;
  }
}

// Within a light, pick_in_light and a point in the piece follow D / Phi_light; points drawn
// uniformly in the light do not.
TEST(PieceTable, DrawsWithinALightByItsTexture) {
  const TexturedQuads quads;
  const Emitters& emitters = *quads.emitters;
  const PieceTable table(emitters);
  const std::uint32_t light = 2;  // of the second quad: most of its texels are black
  std::map<std::array<std::uint32_t, 2>, double> share, observed, uniform;
  std::vector<lightsampler::TexelPiece> pieces;
  emitters.sampler().maps().texel_pieces(light, pieces);
  for (const auto& p : pieces)
    share[{p.texel.x, p.texel.y}] += double(p.density) * p.area * emitters.area(light) / table.light_weight(light);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  constexpr int kDraws = 200000;
  for (int k = 0; k < kDraws; ++k) {
    const PieceTable::Pick pick = table.pick_in_light(light, std::uint64_t(rng()) << 32 | rng());
    ASSERT_EQ(table.light(pick.piece), light);
    const auto b = table.point(pick.piece, float(pick.u), u(rng), u(rng));
    const auto texel = emitters.sampler().maps().texel(light, b.b1, b.b2);
    observed[{texel->x, texel->y}] += 1.0;
    float b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
    const auto elsewhere = emitters.sampler().maps().texel(light, b1, b2);
    uniform[{elsewhere->x, elsewhere->y}] += 1.0;
  }
  std::vector<double> probability, drawn, blind;
  for (const auto& [texel, p] : share) {
    probability.push_back(p);
    drawn.push_back(observed[texel]);
    blind.push_back(uniform[texel]);
  }
  EXPECT_TRUE(follows(drawn, probability, kDraws));
  EXPECT_FALSE(follows(blind, probability, kDraws));
}

TEST(PieceTable, RefusesPastItsLimitSayingWhatToUse) {
  const TexturedQuads quads;
  try {
    PieceTable table(*quads.emitters, 20);
    FAIL() << "a table of " << table.size() << " pieces was built past a limit of 20";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("more than 20 pieces"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("trs"), std::string::npos) << e.what();
  }
}

}  // namespace
