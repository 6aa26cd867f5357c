// The light tree (tracer/src/strategies/light_tree.h) over some hundreds of small emitters at
// different distances and orientations: one-sided and two-sided, textured, some of no power
// (a black texture, a triangle of no area).
//
// Walk. Hypothesis: the pmf the walk reports for a light is the probability that it picks that
// light. Test: 10^6 walks (seed 1 per case) from each of two shading points, with each importance;
// Pearson chi-square of the lights' counts (and of the walks that pick nothing) against 10^6 times
// the pmf that LightTree::pmf recomputes; family alpha 0.01 over the four cases, Sidak. A light
// of no power, or of pmf zero, picked even once fails outright. Every walk's pmf must equal the
// recomputed one bit for bit.
//
// Build. The same nodes whatever the number of threads; every light of positive power in one
// leaf; each node's bounds hold its children's, its power their sum; no leaf deeper than its
// trail can record.
//
// Power. A light's power (Emitters::power) is what physics says: pi L A per emitting face of a
// Lambertian triangle, 4 pi I for a point light; `power` chooses each light in proportion to it,
// two-sided triangles at twice a one-sided one's. Both exact to rounding (relative 1e-6, 1e-12).

#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include <lightsampler/random.h>

#include "scene_builder.h"
#include "strategies/light_choice.h"
#include "strategies/light_tree.h"
#include "strategies/tree_importance.h"
#include "support/chi_square.h"
#include "tracer/emitters.h"

namespace {

using namespace tracer;

/// `count` small triangles scattered in [-4, 4]^2 x [0.3, 6], facing every way, with random UVs
/// over four emissive materials: one-sided and two-sided random textures, a black texture, a
/// constant colour. One in fifty has no area.
Scene scattered_emitters(int count, std::uint64_t seed) {
  Scene scene;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed_unit(-1.0f, 1.0f);
  Material textured;
  textured.emissive_factor = glm::vec3(1.0f);
  textured.emissive_texture.texture = trs_test::add_random_texture(scene, 16, 16, 0.3, seed + 1);
  Material two_sided = textured;
  two_sided.double_sided = true;
  two_sided.emissive_strength = 2.0f;
  Material black = textured;
  black.emissive_texture.texture = trs_test::add_random_texture(scene, 4, 4, 1.0, seed + 2);
  Material plain;
  plain.emissive_factor = glm::vec3(0.9f, 0.5f, 0.2f);
  const std::uint32_t materials[] = {trs_test::add_material(scene, textured), trs_test::add_material(scene, two_sided),
                                     trs_test::add_material(scene, black), trs_test::add_material(scene, plain)};
  Mesh& m = scene.mesh;
  for (int t = 0; t < count; ++t) {
    const glm::vec3 centre(4.0f * signed_unit(rng), 4.0f * signed_unit(rng), 0.3f + 5.7f * unit(rng));
    const float size = 0.05f + 0.4f * unit(rng);
    const bool degenerate = t % 50 == 7;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 offset(signed_unit(rng), signed_unit(rng), signed_unit(rng));
      m.positions.push_back(degenerate ? centre + float(k) * size * glm::vec3(1, 0, 0) : centre + size * offset);
      m.uvs[0].emplace_back(unit(rng), unit(rng));
      m.indices.push_back(std::uint32_t(m.positions.size() - 1));
    }
    m.materials.push_back(materials[t % 7 == 3 ? 2 : t % 3 == 1 ? 1 : t % 5 == 2 ? 3 : 0]);
  }
  return scene;
}

struct Bench {
  Scene scene;
  Emitters emitters;
  std::vector<double> power;

  explicit Bench(int count) : scene(scattered_emitters(count, 5)), emitters(scene, trs_test::kCpuSampler),
                              power(tree_power(emitters, TreePower::exact)) {}
};

/// Below the lights, facing up; and among them, tilted.
const ShadingPoint kShadingPoints[] = {
    {glm::vec3(0.3f, -0.2f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f)},
    {glm::vec3(1.0f, 0.5f, 3.0f), glm::normalize(glm::vec3(0.6f, -0.3f, 0.5f))},
};

constexpr int kLights = 400;
constexpr int kWalks = 1000000;
const double kAlpha = trs_test::sidak_alpha(0.01, 4);

TEST(LightPower, ALambertianFaceEmitsPiRadianceAreaAPointLightFourPiIntensity) {
  Scene scene;
  Material one_sided;
  one_sided.emissive_factor = glm::vec3(1.0f);
  one_sided.emissive_strength = 3.0f;  // luminance 3
  Material two_sided = one_sided;
  two_sided.double_sided = true;
  // Two quads of area 2.
  trs_test::add_quad(scene, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, trs_test::add_material(scene, one_sided));
  trs_test::add_quad(scene, {0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {0, 1, 1}, trs_test::add_material(scene, two_sided));
  scene.lights.push_back({.kind = PunctualLight::Kind::point, .position = {0, 0, 3}, .intensity = glm::vec3(5.0f)});
  const Emitters emitters(scene, trs_test::kCpuSampler);
  ASSERT_EQ(emitters.count(), 4u);
  const double pi = std::numbers::pi;
  EXPECT_NEAR(emitters.power(0) + emitters.power(1), pi * 3.0 * 2.0, 1e-6 * pi * 6.0);
  EXPECT_NEAR(emitters.power(2) + emitters.power(3), 2.0 * pi * 3.0 * 2.0, 1e-6 * pi * 12.0);
  EXPECT_NEAR(emitters.power(4), 4.0 * pi * 5.0, 1e-6 * pi * 20.0);
}

TEST(LightPower, ThePowerChoiceWeighsEachLightByIt) {
  const Bench bench(kLights);
  const Emitters& emitters = bench.emitters;
  double total = 0.0;
  for (std::uint32_t l = 0; l < emitters.count(); ++l) total += emitters.power(l);
  const auto choice = make_power_choice(emitters);
  const ShadingPoint& at = kShadingPoints[0];
  int two_sided = 0;
  for (std::uint32_t l = 0; l < emitters.count(); ++l) {
    const double expected = emitters.power(l) / total;
    EXPECT_NEAR(choice->pmf(l, at), expected, 1e-12 * expected) << l;
    if (emitters.two_sided(l) && emitters.light_density()[l] > 0.0) {
      ++two_sided;
      EXPECT_DOUBLE_EQ(emitters.power(l), 2.0 * std::numbers::pi * emitters.light_density()[l]) << l;
    }
  }
  EXPECT_GT(two_sided, 0);
}

TEST(LightTree, WalkPicksEachLightWithItsPmf) {
  const Bench bench(kLights);
  const LightTree tree(bench.emitters, bench.power);
  for (TreeImportance kind : {TreeImportance::pbrt, TreeImportance::cycles}) {
    const auto importance = make_node_importance(kind, bench.emitters);
    for (const ShadingPoint& at : kShadingPoints) {
      SCOPED_TRACE(to_string(kind));
      // Cell kLights: the walks that pick nothing.
      std::vector<double> observed(kLights + 1, 0.0), expected(kLights + 1, 0.0);
      std::mt19937 rng(1);
      int mismatches = 0;
      for (int i = 0; i < kWalks; ++i) {
        const auto pick = tree.sample(lightsampler::uniform_double(std::uint32_t(rng())), at, *importance);
        if (!pick) {
          observed[kLights] += 1.0;
          continue;
        }
        observed[pick->light] += 1.0;
        mismatches += pick->pmf != tree.pmf(pick->light, at, *importance);
      }
      EXPECT_EQ(mismatches, 0) << "walks whose pmf differs from the recomputed one";
      double total = 0.0;
      for (std::uint32_t light = 0; light < kLights; ++light) {
        const float pmf = tree.pmf(light, at, *importance);
        if (!(bench.power[light] > 0.0)) EXPECT_EQ(pmf, 0.0f) << "light " << light << " has no power";
        expected[light] = double(pmf) * kWalks;
        total += pmf;
      }
      EXPECT_LE(total, 1.0 + 1e-5);
      expected[kLights] = std::max(0.0, 1.0 - total) * kWalks;
      const trs_test::ChiSquareResult result = trs_test::chi_square_test(observed, expected);
      EXPECT_TRUE(result.passes(kAlpha)) << result.describe();
      EXPECT_GT(result.dof, 100.0);
    }
  }
}

/// The scattered emitters with punctual lights among them: points and spots (the tree's leaves)
/// and three directional lights (chosen apart).
Scene scattered_with_punctual_lights(int count, std::uint64_t seed) {
  Scene scene = scattered_emitters(count, seed);
  std::mt19937_64 rng(seed + 3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed_unit(-1.0f, 1.0f);
  for (int i = 0; i < 60; ++i) {
    PunctualLight light;
    light.kind = i % 2 == 0 ? PunctualLight::Kind::point : PunctualLight::Kind::spot;
    light.position = glm::vec3(4.0f * signed_unit(rng), 4.0f * signed_unit(rng), 0.3f + 5.7f * unit(rng));
    light.direction = glm::normalize(glm::vec3(signed_unit(rng), signed_unit(rng), signed_unit(rng)));
    light.intensity = glm::vec3(0.05f + unit(rng));
    light.cos_inner = std::cos(0.2f + 0.3f * unit(rng));
    light.cos_outer = std::cos(0.6f + 0.6f * unit(rng));
    scene.lights.push_back(light);
  }
  for (const float e : {1.0f, 0.5f, 2.0f}) {
    PunctualLight sun;
    sun.kind = PunctualLight::Kind::directional;
    sun.direction = glm::normalize(glm::vec3(signed_unit(rng), signed_unit(rng), -1.0f));
    sun.intensity = glm::vec3(e);
    scene.lights.push_back(sun);
  }
  return scene;
}

// The tree's choice with punctual lights: point and spot lights walked to as leaves, directional
// lights chosen apart with the walk's probability. Hypothesis: the pmf the choice reports is the
// probability that it picks each light. Test: 10^6 picks (seed 1) from each shading point with
// each importance, Pearson chi-square of every light's count (and of the picks of nothing)
// against 10^6 times the pmf; family alpha 0.01 over the four cases, Sidak. The same counts
// against the tree's pmf alone, as if the directional lights took no share, must fail.
TEST(LightTree, ChoiceWithPunctualLeavesPicksEachLightWithItsPmf) {
  Scene scene = scattered_with_punctual_lights(kLights, 5);
  const Emitters emitters(scene, trs_test::kCpuSampler);
  const std::uint32_t lights = emitters.count() + emitters.punctual().count();
  const LightTree tree(emitters, tree_power(emitters, TreePower::exact));
  for (TreeImportance kind : {TreeImportance::pbrt, TreeImportance::cycles}) {
    const auto choice = make_tree_choice(emitters, TreePower::exact, make_node_importance(kind, emitters));
    const auto importance = make_node_importance(kind, emitters);
    for (const ShadingPoint& at : kShadingPoints) {
      SCOPED_TRACE(to_string(kind));
      std::vector<double> observed(lights + 1, 0.0), expected(lights + 1, 0.0), tree_alone(lights + 1, 0.0);
      std::mt19937 rng(1);
      for (int i = 0; i < kWalks; ++i) {
        LightRandom words;
        for (std::uint32_t& w : words) w = std::uint32_t(rng());
        const std::optional<LightPick> pick = choice->pick(words, at);
        observed[pick ? pick->light : lights] += 1.0;
        if (pick) EXPECT_EQ(pick->pmf, choice->pmf(pick->light, at)) << "light " << pick->light;
      }
      double total = 0.0, total_tree = 0.0;
      for (std::uint32_t light = 0; light < lights; ++light) {
        const double pmf = choice->pmf(light, at);
        expected[light] = pmf * kWalks;
        tree_alone[light] = double(tree.pmf(light, at, *importance)) * kWalks;
        total += pmf;
        total_tree += tree_alone[light] / kWalks;
      }
      EXPECT_GT(observed[emitters.count() + 60], 0.0) << "a directional light is never picked";
      expected[lights] = std::max(0.0, 1.0 - total) * kWalks;
      tree_alone[lights] = std::max(0.0, 1.0 - total_tree) * kWalks;
      const trs_test::ChiSquareResult result = trs_test::chi_square_test(observed, expected);
      EXPECT_TRUE(result.passes(kAlpha)) << result.describe();
      EXPECT_GT(result.dof, 100.0);
      EXPECT_FALSE(trs_test::chi_square_test(observed, tree_alone).passes(kAlpha));
    }
  }
}

TEST(LightTree, SameNodesWithAnyNumberOfThreads) {
  const Bench bench(6000);
  std::vector<std::vector<LightTreeNode>> builds;
  // Eight threads even on a machine with fewer cores.
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 8);
  for (int threads : {1, 2, 8}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      const LightTree tree(bench.emitters, bench.power);
      builds.emplace_back(tree.nodes().begin(), tree.nodes().end());
    });
  }
  EXPECT_TRUE(builds[0] == builds[1]) << "1 and 2 threads";
  EXPECT_TRUE(builds[0] == builds[2]) << "1 and 8 threads";
}

/// Whether cone (axis a, cos_a) lies within cone (axis b, cos_b), to within `slack` radians (a
/// cone is kept in single precision, whose cosine near 1 resolves only a few 1e-4 radians).
bool cone_within(glm::vec3 a, float cos_a, glm::vec3 b, float cos_b, double slack) {
  if (cos_b <= -1.0f) return true;
  const double theta_d = std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0));
  return theta_d + std::acos(double(cos_a)) <= std::acos(double(cos_b)) + slack;
}

TEST(LightTree, NodesBoundTheirChildren) {
  const Bench bench(kLights);
  const LightTree tree(bench.emitters, bench.power);
  const std::span<const LightTreeNode> nodes = tree.nodes();
  std::vector<int> leaves(kLights, 0);
  std::size_t lit = 0;
  for (double p : bench.power) lit += p > 0.0;
  ASSERT_EQ(nodes.size(), 2 * lit - 1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const LightTreeNode& node = nodes[i];
    if (node.leaf) {
      ++leaves[node.index];
      EXPECT_EQ(node.bounds.power, float(bench.power[node.index]));
      continue;
    }
    for (const LightTreeNode* child : {&nodes[i + 1], &nodes[node.index]}) {
      const LightBounds& b = child->bounds;
      EXPECT_TRUE(glm::all(glm::lessThanEqual(node.bounds.lower, b.lower)) &&
                  glm::all(glm::greaterThanEqual(node.bounds.upper, b.upper))) << "node " << i;
      EXPECT_TRUE(cone_within(b.axis, b.cos_theta_o, node.bounds.axis, node.bounds.cos_theta_o, 1e-3)) << "node " << i;
      EXPECT_LE(node.bounds.cos_theta_e, b.cos_theta_e);
    }
    EXPECT_EQ(node.bounds.power, nodes[i + 1].bounds.power + nodes[node.index].bounds.power) << "node " << i;
  }
  for (std::uint32_t light = 0; light < kLights; ++light)
    EXPECT_EQ(leaves[light], bench.power[light] > 0.0 ? 1 : 0) << "light " << light;
}

/// The most levels below node `i`.
int depth_below(std::span<const LightTreeNode> nodes, std::uint32_t i) {
  if (nodes[i].leaf) return 0;
  return 1 + std::max(depth_below(nodes, i + 1), depth_below(nodes, nodes[i].index));
}

// 300 lights along a line, ever farther apart and twice as bright every other light: the split
// of least cost peels off a few bright lights at a time and would nest them 77 levels deep,
// more than a light's 64-bit trail holds. The build splits in the middle where a child would
// leave no room, and the walk still agrees with the pmf.
TEST(LightTree, ADeepTreeStaysWithinItsTrails) {
  Scene scene;
  Material plain;
  plain.emissive_factor = glm::vec3(1.0f);
  const std::uint32_t m = trs_test::add_material(scene, plain);
  for (int t = 0; t < 300; ++t) {
    const glm::vec3 c(std::pow(1.08f, float(t)), 0.0f, 0.0f);
    const auto base = std::uint32_t(scene.mesh.positions.size());
    scene.mesh.positions.insert(scene.mesh.positions.end(), {c, c + glm::vec3(0.3f, 0, 0), c + glm::vec3(0, 0.3f, 0)});
    scene.mesh.uvs[0].insert(scene.mesh.uvs[0].end(), {glm::vec2(0), glm::vec2(0), glm::vec2(0)});
    scene.mesh.indices.insert(scene.mesh.indices.end(), {base, base + 1, base + 2});
    scene.mesh.materials.push_back(m);
  }
  const Emitters emitters(scene, trs_test::kCpuSampler);
  std::vector<double> power(300);
  for (int i = 0; i < 300; ++i) power[i] = std::exp2((i - 150) / 2);
  const LightTree tree(emitters, power);
  EXPECT_EQ(depth_below(tree.nodes(), 0), 63);

  const ShadingPoint at{glm::vec3(20.0f, 3.0f, 1.0f), glm::vec3(0.0f, 0.0f, 1.0f)};
  const auto importance = make_node_importance(TreeImportance::pbrt, emitters);
  double total = 0.0;
  for (std::uint32_t light = 0; light < 300; ++light) total += tree.pmf(light, at, *importance);
  EXPECT_NEAR(total, 1.0, 1e-5);
  std::mt19937 rng(2);
  int mismatches = 0;
  for (int i = 0; i < 100000; ++i) {
    const auto pick = tree.sample(lightsampler::uniform_double(std::uint32_t(rng())), at, *importance);
    ASSERT_TRUE(pick);
    mismatches += pick->pmf != tree.pmf(pick->light, at, *importance);
  }
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
