// The adaptive subdivision (lightsampler/refinement.h): its parts tile their triangles, a part's
// sample is the same point of its triangle, the per-triangle outputs are unchanged, the work per
// sample drops, and the samples still follow the density.
//
// Distribution hypothesis H0: samples brought back to the caller's triangles are distributed in
// proportion to the density. Per-triangle chi-square (distribution_check.h) with the seeds of the
// scenarios and trs_test::kDistributionAlpha. The parts' counts are rounded one by one, which
// stratifies a triangle's samples: the multinomial statistic can only be smaller than under
// i.i.d. sampling, so the test is conservative. It is shown to reject the same samples brought
// back without the change of coordinates.

#include <random>

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry.h"
#include "core/host_scene.h"
#include "distribution_check.h"
#include "lightsampler/refinement.h"

using namespace lightsampler;
using trs_test::Scenario;

namespace {

// Splits freely, so that the tests see many levels.
const Refinement kEager{.min_acceptance = 0.9f, .min_texels = 1.0f, .max_levels = 6};

double triangle_area(const MeshView& mesh, std::uint32_t t) {
  double p[3][3];
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) p[k][a] = mesh.positions[3 * std::size_t(mesh.indices[3 * t + k]) + a];
  double n[3];
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    n[a] = (p[1][b] - p[0][b]) * (p[2][c] - p[0][c]) - (p[1][c] - p[0][c]) * (p[2][b] - p[0][b]);
  }
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

Frame generate(Sampler& sampler, const Scenario& s) {
  Frame frame;
  sampler.generate({.seed = s.seed, .target_count = s.target}, frame);
  return frame;
}

std::unique_ptr<Sampler> refined_cpu_sampler(const Scenario& s, const DensityMapView& map,
                                             const Refinement& refinement) {
  return make_refined_sampler(s.mesh.view(), {&map, 1}, refinement,
                              [](const MeshView& parts, std::span<const DensityMapView> maps) {
                                return make_cpu_sampler(parts, maps);
                              });
}

}  // namespace

TEST(Refinement, LeavesAConstantDensityWhole) {
  const trs_test::Mesh mesh = trs_test::quad(2, 1, 0, 0, 1, 1);
  const trs_test::Map map{std::vector<float>(64 * 64, 0.5f), 64, 64};
  const DensityMapView view = map.view();
  const RefinedMesh refined(mesh.view(), {&view, 1}, kEager);
  EXPECT_EQ(refined.levels(), 0u);
  EXPECT_EQ(refined.triangle_count(), 2u);
}

TEST(Refinement, KeepsToItsBudget) {
  const Scenario s = trs_test::scenarios()[2];  // two triangles
  const DensityMapView view = s.map.view();
  Refinement budget = kEager;
  budget.max_triangles = 50;
  const RefinedMesh refined(s.mesh.view(), {&view, 1}, budget);
  EXPECT_GT(refined.levels(), 1u);
  EXPECT_LE(refined.triangle_count(), 50u);
  EXPECT_GT(refined.triangle_count(), 40u);  // it uses the budget
  budget.max_levels = 1;
  EXPECT_EQ(RefinedMesh(s.mesh.view(), {&view, 1}, budget).triangle_count(), 8u);
}

TEST(Refinement, PartsTileTheirTriangles) {
  for (const Scenario& s : trs_test::scenarios()) {
    const DensityMapView view = s.map.view();
    const RefinedMesh refined(s.mesh.view(), {&view, 1}, kEager);
    ASSERT_GT(refined.levels(), 1u) << s.name;
    std::vector<double> area(s.mesh.indices.size() / 3, 0.0);
    for (std::uint32_t part = 0; part < refined.triangle_count(); ++part)
      area[refined.parent(part)] += triangle_area(refined.view(s.mesh.view()), part);
    for (std::uint32_t t = 0; t < area.size(); ++t)
      EXPECT_NEAR(area[t], triangle_area(s.mesh.view(), t), 1e-5 * area[t]) << s.name << ", " << t;
  }
}

TEST(Refinement, APartsSampleIsTheSamePointOfItsTriangle) {
  const Scenario s = trs_test::scenarios()[0];
  const DensityMapView view = s.map.view();
  const RefinedMesh refined(s.mesh.view(), {&view, 1}, kEager);
  for (std::uint32_t part = 0; part < refined.triangle_count(); ++part)
    for (const auto& [b1, b2] : {std::pair{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}, {0.2f, 0.7f}}) {
      const Sample local{part, b1, b2};
      const Sample back = refined.to_parent(local);
      ASSERT_EQ(back.triangle, refined.parent(part));
      ASSERT_GE(back.b1, 0.0f);
      ASSERT_GE(back.b2, 0.0f);
      ASSERT_LE(back.b1 + back.b2, 1.0f);
      const Float3 p = position(refined.view(s.mesh.view()), local), q = position(s.mesh.view(), back);
      const Float2 u = uv(refined.view(s.mesh.view()), local), w = uv(s.mesh.view(), back);
      EXPECT_NEAR(p.x, q.x, 1e-5f);
      EXPECT_NEAR(p.y, q.y, 1e-5f);
      EXPECT_NEAR(p.z, q.z, 1e-5f);
      EXPECT_NEAR(u.x, w.x, 1e-5f);
      EXPECT_NEAR(u.y, w.y, 1e-5f);
    }
}

TEST(Refinement, PerTriangleOutputsAreTheTrianglesOwn) {
  for (const Scenario& s : trs_test::scenarios()) {
    const DensityMapView view = s.map.view();
    const Frame plain = generate(*make_cpu_sampler(s.mesh.view(), {&view, 1}), s);
    const Frame refined = generate(*refined_cpu_sampler(s, view, kEager), s);
    ASSERT_EQ(refined.expected_counts.size(), plain.expected_counts.size()) << s.name;
    EXPECT_NEAR(refined.expected_total, plain.expected_total, 1e-5 * plain.expected_total);
    std::uint64_t total = 0;
    for (std::size_t t = 0; t < plain.expected_counts.size(); ++t) {
      EXPECT_NEAR(refined.expected_counts[t], plain.expected_counts[t],
                  1e-5 * plain.expected_counts[t] + 1e-12)
          << s.name << ", triangle " << t;
      // A part's maximum is one of its triangle's texels, and some part holds the largest.
      EXPECT_EQ(refined.max_density[t], plain.max_density[t]) << s.name << ", triangle " << t;
      total += refined.counts[t];
    }
    EXPECT_EQ(total, refined.sample_count) << s.name;
    for (const Sample& x : refined.samples) ASSERT_LT(x.triangle, plain.expected_counts.size());
  }
}

TEST(Refinement, RaisesTheAcceptance) {
  // Two large triangles under two thin strokes (neon-like): few candidates land on them unless
  // the triangles are split around them. (A map without spatial structure, texel noise, gains
  // little: every part still sees bright and dark texels.)
  const trs_test::Mesh mesh = trs_test::quad(2, 1, 0, 0, 1, 1);
  trs_test::Map map{std::vector<float>(128 * 64, 0.0f), 128, 64};
  for (std::uint32_t x = 10; x < 110; ++x) map.texels[20 * 128 + x] = map.texels[21 * 128 + x] = 1.0f;
  for (std::uint32_t y = 5; y < 60; ++y) map.texels[y * 128 + 70] = 2.0f;
  const DensityMapView view = map.view();
  const Scenario s{"strokes", mesh, map, 1e5, 7};
  const Frame plain = generate(*make_cpu_sampler(mesh.view(), {&view, 1}), s);
  const Frame refined = generate(*refined_cpu_sampler(s, view, {.min_acceptance = 0.5f}), s);
  const double before = double(plain.sample_count) / double(plain.candidates);
  const double after = double(refined.sample_count) / double(refined.candidates);
  EXPECT_LT(before, 0.05);
  EXPECT_GT(after, 0.3);
}

TEST(Refinement, SplitsAgainForAChangedMap) {
  // A stroke that moves, as on an animated texture: after update_map the sampler draws what one
  // built on the new map draws, sample for sample, and keeps the new stroke's acceptance.
  const trs_test::Mesh mesh = trs_test::quad(2, 1, 0, 0, 1, 1);
  const auto stroke = [](std::uint32_t row) {
    trs_test::Map map{std::vector<float>(128 * 64, 0.0f), 128, 64};
    for (std::uint32_t x = 10; x < 110; ++x) map.texels[row * 128 + x] = 1.0f;
    return map;
  };
  const trs_test::Map first = stroke(20), moved = stroke(45);
  const DensityMapView first_view = first.view(), moved_view = moved.view();
  const Scenario s{"moving stroke", mesh, moved, 1e5, 7};
  auto updated = refined_cpu_sampler(s, first_view, {.min_acceptance = 0.5f});
  generate(*updated, s);
  updated->update_map(0, moved_view);
  const Frame got = generate(*updated, s), want = generate(*refined_cpu_sampler(s, moved_view, {.min_acceptance = 0.5f}), s);
  ASSERT_EQ(got.sample_count, want.sample_count);
  for (std::size_t i = 0; i < want.samples.size(); ++i) {
    const Sample &a = got.samples[i], &b = want.samples[i];
    ASSERT_TRUE(a.triangle == b.triangle && a.b1 == b.b1 && a.b2 == b.b2) << "sample " << i;
  }
  EXPECT_GT(double(got.sample_count) / double(got.candidates), 0.3);
}

TEST(Refinement, SamplesMatchTheDensity) {
  for (const Scenario& s : trs_test::scenarios()) {
    const DensityMapView view = s.map.view();
    const Frame frame = generate(*refined_cpu_sampler(s, view, kEager), s);
    const auto result = trs_test::test_per_triangle(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name << ": too few cells to have power";
    EXPECT_TRUE(result.passes(trs_test::kDistributionAlpha)) << s.name << "\n" << result.describe();
  }
}

TEST(Refinement, RejectsPartSamplesKeptInThePartsCoordinates) {
  const Scenario s = trs_test::scenarios()[2];
  const DensityMapView view = s.map.view();
  const RefinedMesh refined(s.mesh.view(), {&view, 1}, kEager);
  Frame frame;
  make_cpu_sampler(refined.view(s.mesh.view()), {&view, 1})->generate({.seed = s.seed, .target_count = s.target}, frame);
  std::vector<Sample> right, wrong;
  for (const Sample& x : frame.samples) {
    right.push_back(refined.to_parent(x));
    wrong.push_back({refined.parent(x.triangle), x.b1, x.b2});
  }
  EXPECT_TRUE(trs_test::test_per_triangle(s, right).passes(trs_test::kDistributionAlpha));
  EXPECT_FALSE(trs_test::test_per_triangle(s, wrong).passes(trs_test::kDistributionAlpha));
}

TEST(Refinement, NearTheTexelScaleKeepsOnlySplitsThatPay) {
  // Two triangles of 8 texels each on a 4 x 4 map. Texel noise in [0.6, 1]: every part still
  // sees a texel near the maximum, so a split lowers the candidates by far less than 1.25 and is
  // not kept (it is, with a gain of 1). One bright texel among zeros: a split cuts the
  // candidates of the parts away from it to nothing, and is kept.
  const trs_test::Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  trs_test::Map noise{std::vector<float>(16), 4, 4};
  std::mt19937_64 rng(8);
  for (float& t : noise.texels) t = std::uniform_real_distribution<float>(0.6f, 1.0f)(rng);
  const DensityMapView noisy = noise.view();
  const Refinement refine{.min_acceptance = 0.95f, .min_texels = 0.25f};
  EXPECT_EQ(RefinedMesh(mesh.view(), {&noisy, 1}, refine).levels(), 0u);
  Refinement always = refine;
  always.min_split_gain = 1.0f;
  EXPECT_GT(RefinedMesh(mesh.view(), {&noisy, 1}, always).levels(), 0u);
  trs_test::Map spot{std::vector<float>(16, 0.0f), 4, 4};
  spot.texels[5] = 1.0f;
  const DensityMapView sparse = spot.view();
  EXPECT_GT(RefinedMesh(mesh.view(), {&sparse, 1}, refine).levels(), 0u);
}

TEST(Refinement, KeepsASplitThatPaysOnlyOneRoundLater) {
  // One triangle, UVs (0,0), (1,0), (0,1), over 2048 texels of a 64 x 64 map lit only along the
  // row and the column of texels at 3/8: the strokes cross every quarter of the triangle, so one
  // split keeps the bound where it was, and is not kept when no second round may follow. Two
  // rounds leave most parts' parts off the strokes, and the first split is kept for them.
  trs_test::Mesh mesh;
  const float corners[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, uvs[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  mesh.add_triangle(corners, uvs);
  trs_test::Map cross{std::vector<float>(64 * 64, 0.0f), 64, 64};
  for (int i = 0; i < 64; ++i) cross.texels[24 * 64 + i] = cross.texels[i * 64 + 24] = 1.0f;
  const DensityMapView view = cross.view();
  Refinement one_round{.min_acceptance = 0.9f, .min_texels = 0.25f, .gain_texels = 1e9f, .max_levels = 1};
  EXPECT_EQ(RefinedMesh(mesh.view(), {&view, 1}, one_round).levels(), 0u);
  Refinement two_rounds = one_round;
  two_rounds.max_levels = 2;
  EXPECT_EQ(RefinedMesh(mesh.view(), {&view, 1}, two_rounds).levels(), 2u);
}

// The cost model (Refinement::cost_model, the tools' `auto`).

namespace {

/// Two large triangles under two thin strokes: the sparse case that splitting is for.
struct Strokes {
  trs_test::Mesh mesh = trs_test::quad(2, 1, 0, 0, 1, 1);
  trs_test::Map map{std::vector<float>(128 * 64, 0.0f), 128, 64};
  Strokes() {
    for (std::uint32_t x = 10; x < 110; ++x) map.texels[20 * 128 + x] = map.texels[21 * 128 + x] = 1.0f;
    for (std::uint32_t y = 5; y < 60; ++y) map.texels[y * 128 + 70] = 2.0f;
  }
};

/// Expected candidates a frame of `samples` draws on the parts `refinement` makes of `mesh`, plus
/// the parts' own work.
double frame_cost(const MeshView& mesh, const DensityMapView& map, const Refinement& refinement, double samples,
                  float part_cost) {
  const RefinedMesh refined(mesh, {&map, 1}, refinement);
  const MeshView parts = refined.view(mesh);
  Frame frame;
  make_cpu_sampler(parts, {&map, 1})->generate({.seed = 1, .realize = false}, frame);
  double bound = 0.0;
  for (std::uint32_t t = 0; t < refined.triangle_count(); ++t)
    bound += double(frame.max_density[t]) * triangle_area(parts, t);
  return samples * bound / frame.expected_total + part_cost * refined.triangle_count();
}

}  // namespace

TEST(RefinementCostModel, SplitsOnlyWhereTheFrameHasSamplesToSave) {
  // Two triangles, the map bright on its left half and a quarter as bright on its right: an
  // acceptance of 0.62, so a frame wastes 0.6 candidates a sample. Ten samples cannot pay for
  // the three parts of a split; a hundred thousand can pay for many.
  const trs_test::Mesh mesh = trs_test::quad(2, 1, 0, 0, 1, 1);
  trs_test::Map halves{std::vector<float>(64 * 64, 0.25f), 64, 64};
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 32; ++x) halves.texels[y * 64 + x] = 1.0f;
  const DensityMapView view = halves.view();
  EXPECT_EQ(RefinedMesh(mesh.view(), {&view, 1}, auto_refinement(10)).levels(), 0u);
  EXPECT_GT(RefinedMesh(mesh.view(), {&view, 1}, auto_refinement(1e5)).levels(), 0u);
  // Unknown frames: the acceptance rules, as `--refine 0.85` splits.
  const Strokes strokes;
  const DensityMapView sparse = strokes.map.view();
  const RefinedMesh unknown(strokes.mesh.view(), {&sparse, 1}, auto_refinement(0));
  const RefinedMesh rules(strokes.mesh.view(), {&sparse, 1}, {.min_acceptance = kAutoMinAcceptance});
  EXPECT_GT(unknown.levels(), 0u);
  EXPECT_EQ(unknown.triangle_count(), rules.triangle_count());
}

TEST(RefinementCostModel, PartsGrowWithTheSamplesAndKeepToTheirBudget) {
  const Strokes strokes;
  const DensityMapView view = strokes.map.view();
  std::uint32_t previous = 2;
  for (double samples : {1e3, 1e4, 1e5}) {
    const Refinement refinement = auto_refinement(samples);
    const RefinedMesh refined(strokes.mesh.view(), {&view, 1}, refinement);
    EXPECT_GE(refined.triangle_count(), previous) << samples;
    EXPECT_LE(refined.triangle_count(), 2 + refinement.parts_per_sample * samples) << samples;
    previous = refined.triangle_count();
  }
  EXPECT_GT(previous, 100u);
}

TEST(RefinementCostModel, ExploresOnlyWhatAFrameRepays) {
  // Hypothesis: a split is explored only where the candidates a frame could save on it repay
  // measuring its four parts. Each of the strokes' two triangles covers 4096 texels: measuring
  // its parts (12 candidates a texel) costs more than 300 samples waste on it (about 50 candidates
  // a sample), not 3,000.
  const Strokes strokes;
  const DensityMapView view = strokes.map.view();
  EXPECT_EQ(RefinedMesh(strokes.mesh.view(), {&view, 1}, auto_refinement(300)).levels(), 0u);
  EXPECT_GT(RefinedMesh(strokes.mesh.view(), {&view, 1}, auto_refinement(3e3)).levels(), 0u);
  // Measuring free, the same frame explores.
  Refinement free_measures = auto_refinement(300);
  free_measures.measure_cost = free_measures.measure_texel_cost = 0.0f;
  EXPECT_GT(RefinedMesh(strokes.mesh.view(), {&view, 1}, free_measures).levels(), 0u);
}

TEST(RefinementCostModel, ItsPartsCostLessThanTheWholeOrOneRoundOfSplits) {
  // Hypothesis: the kept splits are the cheapest the explored ones allow; in particular cheaper
  // per frame, as the model counts it, than no subdivision and than a subdivision that splits
  // every part it tried one round further (the acceptance rules at 0.85, which split blindly).
  // From 3e4 samples: fewer cannot repay exploring a split here (ExploresOnlyWhatAFrameRepays).
  const Strokes strokes;
  const DensityMapView view = strokes.map.view();
  for (double samples : {3e4, 3e5, 3e6}) {
    const Refinement refinement = auto_refinement(samples);
    const double cost = frame_cost(strokes.mesh.view(), view, refinement, samples, refinement.part_cost);
    const double whole = frame_cost(strokes.mesh.view(), view, {}, samples, refinement.part_cost);
    const double blind = frame_cost(strokes.mesh.view(), view, kEager, samples, refinement.part_cost);
    EXPECT_LT(cost, whole) << samples;
    EXPECT_LT(cost, blind) << samples;
  }
}

TEST(Refinement, APointClearOfTexelEdgesReadsItsTexelEitherWay) {
  // Hypothesis: where core::clear_of_texel_edges says a part's point, brought back to its
  // triangle, lies clear of its texel's edges, the point reads the same texel in the part's
  // coordinates as in the triangle's; the refined sampler then skips the full check. The points:
  // each part's, moved in x to a texel edge, then off it by 0 to 8 margins (seed 7). Those on the
  // edge itself must read another texel sometimes, or the test could not tell a margin too small.
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int clear = 0, near_edge_clear = 0, differ_on_edge = 0;
  for (const Scenario& s : trs_test::scenarios()) {
    const DensityMapView view = s.map.view();
    const RefinedMesh refined(s.mesh.view(), {&view, 1}, kEager);
    const core::HostScene parts(refined.view(s.mesh.view()), {&view, 1}), triangles(s.mesh.view(), {&view, 1});
    for (std::uint32_t part = 0; part < refined.triangle_count(); ++part) {
      const core::TexelTriangle& pt = parts.texel_triangles()[part];
      if (!(std::abs(pt.edge1[0]) > 0.0f)) continue;
      for (int k = 0; k < 16; ++k) {
        Sample local{part, 0.5f * u(random), 0.5f * u(random)};
        const core::TexelTriangle& tt = triangles.texel_triangles()[refined.to_parent(local).triangle];
        const float magnitude = std::max(std::abs(tt.origin[0]) + std::abs(tt.edge1[0]) + std::abs(tt.edge2[0]),
                                         std::abs(tt.origin[1]) + std::abs(tt.edge1[1]) + std::abs(tt.edge2[1]));
        const float x = core::texel_space_point(pt, local.b1, local.b2)[0];
        const float offset = float(k % 9) * magnitude * 0x1p-18f * (k < 9 ? 1.0f : -1.0f);
        local.b1 += (std::round(x) + offset - x) / pt.edge1[0];
        if (local.b1 < 0.0f || local.b1 + local.b2 > 1.0f) continue;
        const Sample back = refined.to_parent(local);
        const std::optional<Texel> drawn = parts.texel(part, local.b1, local.b2),
                                   read = triangles.texel(back.triangle, back.b1, back.b2);
        const bool same = !drawn || (read && read->map == drawn->map && read->x == drawn->x && read->y == drawn->y);
        if (k % 9 == 0 && !same) ++differ_on_edge;
        if (!core::clear_of_texel_edges(tt, back.b1, back.b2)) continue;
        ++clear;
        if (k % 9 <= 2) ++near_edge_clear;
        ASSERT_TRUE(same) << s.name << ", part " << part << " at (" << local.b1 << ", " << local.b2 << ")";
      }
    }
  }
  EXPECT_GT(clear, 1000);
  EXPECT_GT(near_edge_clear, 100);  // points within two margins of an edge that it calls clear
  EXPECT_GT(differ_on_edge, 0);
  std::printf("clear %d (within two margins of an edge %d); on an edge, another texel %d times\n", clear,
              near_edge_clear, differ_on_edge);
}

TEST(Refinement, ItsMeasuresAreTheBackendsCounts) {
  // Hypothesis: the subdivision's measure of each part it keeps is, to the bit, what the CPU
  // backend's counting pass gives over the parts (the refined sampler hands it over instead of
  // counting again), whether it split (the eager rules, the cost model) or not.
  for (const Scenario& s : trs_test::scenarios()) {
    const DensityMapView view = s.map.view();
    for (const Refinement& refinement : {kEager, auto_refinement(s.target), auto_refinement(1.0)}) {
      const RefinedMesh refined(s.mesh.view(), {&view, 1}, refinement);
      Frame counted;
      make_cpu_sampler(refined.view(s.mesh.view()), {&view, 1})->generate({.seed = 1, .realize = false}, counted);
      ASSERT_EQ(refined.expected_counts().size(), refined.triangle_count()) << s.name;
      for (std::uint32_t t = 0; t < refined.triangle_count(); ++t) {
        EXPECT_EQ(refined.expected_counts()[t], counted.expected_counts[t]) << s.name << ", part " << t;
        EXPECT_EQ(refined.max_density()[t], counted.max_density[t]) << s.name << ", part " << t;
      }
    }
  }
}

TEST(Refinement, AFrameUsesTheSubdivisionsMeasures) {
  // The refined sampler's first frame counts nothing; its per-triangle outputs and total are
  // those of a sampler that counted (PerTriangleOutputsAreTheTrianglesOwn checks them against the
  // caller's mesh), as is a frame that asks for another overlap formula and so counts again.
  const Scenario s = trs_test::scenarios()[2];
  const DensityMapView view = s.map.view();
  const std::unique_ptr<Sampler> sampler = refined_cpu_sampler(s, view, kEager);
  Frame first, recounted;
  sampler->generate({.seed = 1, .realize = false}, first);
  EXPECT_FALSE(first.counting_used.has_value());
  sampler->generate({.seed = 1, .overlap = Overlap::clipping, .realize = false}, recounted);
  sampler->generate({.seed = 1, .realize = false}, recounted);
  EXPECT_EQ(recounted.counting_used, Counting::cpu);
  EXPECT_EQ(first.expected_total, recounted.expected_total);
  for (std::size_t t = 0; t < first.expected_counts.size(); ++t) {
    EXPECT_EQ(first.expected_counts[t], recounted.expected_counts[t]) << t;
    EXPECT_EQ(first.max_density[t], recounted.max_density[t]) << t;
  }
  EXPECT_THROW(make_cpu_sampler(s.mesh.view(), {&view, 1})->use_counts({}, {}), std::invalid_argument);
}

TEST(RefinementCostModel, SamplesMatchTheDensity) {
  int split = 0;
  for (const Scenario& s : trs_test::scenarios()) {
    const DensityMapView view = s.map.view();
    split += RefinedMesh(s.mesh.view(), {&view, 1}, auto_refinement(s.target)).levels() > 0;
    const Frame frame = generate(*refined_cpu_sampler(s, view, auto_refinement(s.target)), s);
    const auto result = trs_test::test_per_triangle(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name << ": too few cells to have power";
    EXPECT_TRUE(result.passes(trs_test::kDistributionAlpha)) << s.name << "\n" << result.describe();
  }
  EXPECT_GT(split, 0) << "no scenario was split: the test would not see the subdivision";
}
