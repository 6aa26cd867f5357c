// The Vulkan backend against the CPU backend (its oracle) and against the density itself. Runs
// on any Vulkan device; in CI on lavapipe, where LIGHTSAMPLER_REQUIRE_VULKAN=1 turns a missing
// device into a failure instead of a skip.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "distribution_check.h"
#include "lightsampler/vulkan.h"
#include "vulkan/context.h"
#include "vulkan/layouts.h"

using namespace lightsampler;
using trs_test::Map;
using trs_test::Mesh;

namespace {

std::vector<DensityMapView> views(const std::vector<Map>& maps) {
  std::vector<DensityMapView> v;
  for (const Map& m : maps) v.push_back(m.view());
  return v;
}

Frame generate(Sampler& sampler, FrameRequest request) {
  Frame frame;
  sampler.generate(request, frame);
  return frame;
}

class VulkanSampler : public ::testing::Test {
 protected:
  void SetUp() override {
    validation_messages_ = vk::validation_message_count();
    const Mesh quad = trs_test::quad(1, 1, 0, 0, 1, 1);
    const Map map{{1.0f}, 1, 1};
    try {
      gpu({quad}, {map});
    } catch (const VulkanUnavailable& e) {
      const char* required = std::getenv("LIGHTSAMPLER_REQUIRE_VULKAN");
      if (required && std::string(required) == "1") FAIL() << "Vulkan is required here: " << e.what();
      GTEST_SKIP() << "no Vulkan device: " << e.what();
    }
  }

  void TearDown() override {
    EXPECT_EQ(vk::validation_message_count(), validation_messages_) << "the validation layer reported problems";
  }

  static std::unique_ptr<Sampler> gpu(const Mesh& mesh, const std::vector<Map>& maps) {
    return make_vulkan_sampler(mesh.view(), views(maps), {.validation = true});
  }
  static std::unique_ptr<Sampler> cpu(const Mesh& mesh, const std::vector<Map>& maps) {
    return make_cpu_sampler(mesh.view(), views(maps));
  }

 private:
  std::size_t validation_messages_ = 0;
};

/// Small triangles: corners within `spread` of centers uniform in [lo, hi]^2 (UV units).
Mesh scattered_triangles(int count, float lo, float hi, float spread, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> center(lo, hi), corner(-spread, spread), pos(-1.0f, 1.0f);
  Mesh m;
  for (int t = 0; t < count; ++t) {
    const float u = center(rng), v = center(rng);
    float p[3][3], uv[3][2];
    for (int k = 0; k < 3; ++k) {
      for (float& x : p[k]) x = pos(rng);
      uv[k][0] = u + corner(rng);
      uv[k][1] = v + corner(rng);
    }
    m.add_triangle(p, uv);
  }
  return m;
}

/// N-bar_T and D_T^max from every counting path against the CPU backend (automatic mixes the
/// per-triangle and compute paths by triangle size: the meshes below have small and large ones). The GPU sums float
/// contributions with float atomics: tolerance relative 1e-4 of the triangle's count (or of
/// the largest count, for counts near zero). D_T^max is the largest texel read over the
/// triangle's cells of positive overlap: the same texels on both backends, so equal. Either
/// backend measures overlaps by `overlap`.
void expect_counts_agree(const Mesh& mesh, const std::vector<Map>& maps, Overlap overlap = Overlap::closed_form) {
  const Frame reference =
      generate(*make_cpu_sampler(mesh.view(), views(maps)), {.overlap = overlap, .realize = false});
  double largest = 0;
  for (double e : reference.expected_counts) largest = std::max(largest, e);
  auto sampler = make_vulkan_sampler(mesh.view(), views(maps), {.validation = true});
  for (Counting path : {Counting::automatic, Counting::compute, Counting::raster, Counting::per_triangle}) {
    SCOPED_TRACE(to_string(path));
    const Frame f = generate(*sampler, {.overlap = overlap, .realize = false, .vulkan = {.counting = path}});
    EXPECT_EQ(f.counting_used, path);
    ASSERT_EQ(f.expected_counts.size(), reference.expected_counts.size());
    for (std::size_t t = 0; t < f.expected_counts.size(); ++t) {
      const double want = reference.expected_counts[t];
      EXPECT_NEAR(f.expected_counts[t], want, 1e-4 * std::max(want, 1e-3 * largest)) << "triangle " << t;
      EXPECT_EQ(f.max_density[t], reference.max_density[t]) << "triangle " << t;
    }
    EXPECT_NEAR(f.expected_total, reference.expected_total, 1e-4 * reference.expected_total);
  }
}

/// Every texel different (1 + its index), so reading a wrong one changes D_T^max and the samples.
Map distinct_map(std::uint32_t w, std::uint32_t h, Addressing addressing) {
  Map m{std::vector<float>(std::size_t(w) * h), w, h, addressing};
  for (std::size_t i = 0; i < m.texels.size(); ++i) m.texels[i] = 1.0f + float(i);
  return m;
}

/// Samples of each triangle, sorted: the unordered scan leaves their order unspecified.
std::vector<std::vector<std::tuple<float, float>>> samples_by_triangle(const Frame& f) {
  std::vector<std::vector<std::tuple<float, float>>> v(f.counts.size());
  for (const Sample& s : f.samples) v[s.triangle].emplace_back(s.b1, s.b2);
  for (auto& samples : v) std::sort(samples.begin(), samples.end());
  return v;
}

/// TRS: a triangle that both backends gave the same N_T and D_T^max has the same samples, bit for
/// bit (same Philox streams, same texel reads). Returns how many triangles were compared.
std::size_t expect_same_samples_where_counts_agree(const Frame& want, const Frame& got) {
  const auto a = samples_by_triangle(want), b = samples_by_triangle(got);
  std::size_t compared = 0;
  for (std::size_t t = 0; t < a.size(); ++t) {
    if (want.counts[t] != got.counts[t] || want.max_density[t] != got.max_density[t]) continue;
    EXPECT_EQ(b[t], a[t]) << "triangle " << t;
    ++compared;
  }
  return compared;
}

/// Plain rejection sampling: sample i is slot i of the output's candidate stream, so both
/// backends draw the same sample i (over the samples both drew).
void expect_same_samples_in_order(const Frame& want, const Frame& got) {
  for (std::size_t i = 0; i < std::min(want.samples.size(), got.samples.size()); ++i) {
    const Sample &a = want.samples[i], &b = got.samples[i];
    ASSERT_TRUE(a.triangle == b.triangle && a.b1 == b.b1 && a.b2 == b.b2) << "sample " << i;
  }
}

}  // namespace

TEST_F(VulkanSampler, CountsAgreeWithTheCpuInsideTheUnitSquare) {
  expect_counts_agree(trs_test::random_triangles(300, 0.0f, 1.0f, 1), {trs_test::random_map(37, 23, 0.4, 2)});
}

// Polygon clipping and the paper's Eq. 6 (Figure 11) on every counting path: the CPU backend's
// counts by the same formula, which for clipping are the closed form's.
TEST_F(VulkanSampler, OverlapFormulasCountAsOnTheCpu) {
  for (Overlap overlap : {Overlap::clipping, Overlap::sdf}) {
    SCOPED_TRACE(to_string(overlap));
    expect_counts_agree(trs_test::random_triangles(300, 0.0f, 1.0f, 1), {trs_test::random_map(37, 23, 0.4, 2)}, overlap);
  }
}

TEST_F(VulkanSampler, CountsAgreeWithTheCpuBeyondTheUnitSquare) {
  Map clamped = trs_test::random_map(16, 9, 0.3, 4), mirrored = clamped;
  clamped.addressing = Addressing::clamp;
  mirrored.addressing = Addressing::mirror;
  expect_counts_agree(trs_test::random_triangles(200, -1.5f, 2.5f, 3), {trs_test::random_map(16, 9, 0.3, 4)});
  expect_counts_agree(trs_test::random_triangles(200, -1.5f, 2.5f, 5), {clamped});
  expect_counts_agree(trs_test::random_triangles(200, -1.5f, 2.5f, 6), {mirrored});
}

TEST_F(VulkanSampler, CountsAgreeWithTheCpuOnSliversTinyAndHugeTriangles) {
  Mesh mesh = trs_test::random_triangles(100, 0.3f, 0.3005f, 7);  // inside a texel or two
  const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1e-3f, 0}};
  const float sliver[3][2] = {{0.01f, 0.5f}, {0.99f, 0.5001f}, {0.5f, 0.5003f}};
  mesh.add_triangle(p, sliver);
  const float huge[3][2] = {{0, 0}, {1, 0}, {0, 1}};  // half of a 256^2 map
  mesh.add_triangle(p, huge);
  expect_counts_agree(mesh, {trs_test::random_map(256, 256, 0.2, 8)});
}

/// Equilateral triangles of UV radius 0.1 to 0.2, centred uniformly in [0.2, 0.8]^2 and turned at
/// random: small, and never slivers (whose float and double areas differ by more than 1e-4).
Mesh small_round_triangles(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> center(0.2f, 0.8f), radius(0.1f, 0.2f), turn(0.0f, 2.1f), pos(-1.0f, 1.0f);
  Mesh m;
  for (int t = 0; t < count; ++t) {
    const float u = center(rng), v = center(rng), r = radius(rng), a = turn(rng);
    float p[3][3], uv[3][2];
    for (int k = 0; k < 3; ++k) {
      for (float& x : p[k]) x = pos(rng);
      uv[k][0] = u + r * std::cos(a + 2.0944f * float(k));
      uv[k][1] = v + r * std::sin(a + 2.0944f * float(k));
    }
    m.add_triangle(p, uv);
  }
  return m;
}

TEST_F(VulkanSampler, CountsAgreeWithTheCpuOnAManyTriangleMesh) {
  // Enough triangles for automatic counting to count the small ones one invocation each, and a
  // large one that the balanced cell pass takes.
  Mesh mesh = small_round_triangles(70000, 23);
  const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const float large[3][2] = {{-5.0f, -4.0f}, {6.0f, -4.0f}, {0.0f, 4.6f}};  // 99 x 61 cells, wrapped
  mesh.add_triangle(p, large);
  expect_counts_agree(mesh, {trs_test::random_map(9, 7, 0.3, 24)});
}

TEST_F(VulkanSampler, CountsAgreeWithTheCpuWithSeveralMaps) {
  Mesh mesh = trs_test::random_triangles(90, 0.0f, 1.0f, 9);
  for (std::size_t t = 0; t < 90; ++t) mesh.triangle_maps.push_back(t % 3 == 2 ? kNoMap : std::uint32_t(t % 3));
  Map scaled = trs_test::random_map(8, 8, 0.0, 11);
  scaled.scale = 3.5f;
  expect_counts_agree(mesh, {trs_test::random_map(20, 30, 0.3, 10), scaled});
}

TEST_F(VulkanSampler, SamplesFollowTheDensity) {
  for (const trs_test::Scenario& s : trs_test::scenarios()) {
    auto sampler = gpu(s.mesh, {s.map});
    for (Counting path : {Counting::compute, Counting::raster}) {
      const Frame f = generate(*sampler, {.seed = s.seed, .target_count = s.target, .vulkan = {.counting = path}});
      EXPECT_EQ(f.exhausted, 0u) << s.name;
      const auto result = trs_test::test_per_triangle(s, f.samples.span());
      EXPECT_GT(result.dof, 100) << s.name;
      EXPECT_TRUE(result.passes(trs_test::kDistributionAlpha)) << s.name << ", " << to_string(path) << "\n"
                                                               << result.describe();
    }
    const Frame rs = generate(*sampler, {.seed = s.seed, .target_count = s.target, .method = Method::rejection});
    EXPECT_EQ(rs.exhausted, 0u) << s.name;
    const auto result = trs_test::test_all_cells(s, rs.samples.span());
    EXPECT_TRUE(result.passes(trs_test::kDistributionAlpha)) << s.name << ", rejection\n" << result.describe();
  }
}

TEST_F(VulkanSampler, NaiveStratificationAndFrsFollowTheDensity) {
  for (const trs_test::Scenario& s : trs_test::scenarios()) {
    auto sampler = gpu(s.mesh, {s.map});
    const Frame naive = generate(*sampler, {.seed = s.seed, .target_count = s.target, .method = Method::naive});
    EXPECT_EQ(naive.exhausted, 0u) << s.name;
    const auto strata = trs_test::test_per_triangle(s, naive.samples.span());
    EXPECT_GT(strata.dof, 100) << s.name;
    EXPECT_TRUE(strata.passes(trs_test::kDistributionAlpha)) << s.name << ", naive\n" << strata.describe();
    const Frame frs = generate(*sampler, {.seed = s.seed, .target_count = s.target, .method = Method::frs});
    EXPECT_EQ(frs.exhausted, 0u) << s.name;
    EXPECT_GT(frs.setup_bytes, 0u) << s.name;
    const auto all = trs_test::test_all_cells(s, frs.samples.span());
    EXPECT_GT(all.dof, 100) << s.name;
    EXPECT_TRUE(all.passes(trs_test::kDistributionAlpha)) << s.name << ", frs\n" << all.describe();
  }
}

TEST_F(VulkanSampler, RejectsNaiveStratificationAndFrsOfAnotherDensity) {
  // Both samplers run on the square root of the map: the same support, the wrong shares (naive
  // stratification's pieces weighted as the CPU test's wrong variant weights them), which the
  // checks against the true density must catch on the device's samples too.
  const trs_test::Scenario s = trs_test::scenarios()[2];
  Map flatter = s.map;
  for (float& texel : flatter.texels) texel = std::sqrt(texel);
  auto sampler = gpu(s.mesh, {flatter});
  const Frame naive = generate(*sampler, {.seed = s.seed, .target_count = s.target, .method = Method::naive});
  EXPECT_FALSE(trs_test::test_per_triangle(s, naive.samples.span()).passes(trs_test::kDistributionAlpha));
  const Frame frs = generate(*sampler, {.seed = s.seed, .target_count = s.target, .method = Method::frs});
  EXPECT_FALSE(trs_test::test_all_cells(s, frs.samples.span()).passes(trs_test::kDistributionAlpha));
}

TEST_F(VulkanSampler, RefinedSamplesFollowTheDensity) {
  // make_sampler with a refinement: the device samples the parts, the host brings them back.
  for (const trs_test::Scenario& s : trs_test::scenarios()) {
    const DensityMapView view = s.map.view();
    auto sampler = make_sampler(s.mesh.view(), {&view, 1},
                                {.backend = Backend::vulkan,
                                 .cpu = {},
                                 .vulkan = {.validation = true},
                                 .refinement = {.min_acceptance = 0.9f, .min_texels = 1.0f}});
    const Frame f = generate(*sampler, {.seed = s.seed, .target_count = s.target});
    EXPECT_EQ(f.exhausted, 0u) << s.name;
    ASSERT_EQ(f.counts.size(), s.mesh.indices.size() / 3) << s.name;
    const auto result = trs_test::test_per_triangle(s, f.samples.span());
    EXPECT_TRUE(result.passes(trs_test::kDistributionAlpha)) << s.name << "\n" << result.describe();
  }
}

TEST_F(VulkanSampler, SameSamplesAsTheCpuWhereTheCountsAgree) {
  // Same Philox streams, same texel reads: a triangle given the same N_T and D_T^max by both
  // backends gets bit-identical samples (the unordered scan leaves their order unspecified).
  const Mesh mesh = trs_test::random_triangles(200, 0.0f, 1.0f, 12);
  const std::vector<Map> maps = {trs_test::random_map(32, 32, 0.3, 13)};
  const FrameRequest request{.seed = 5, .target_count = 100000};
  const Frame a = generate(*cpu(mesh, maps), request), b = generate(*gpu(mesh, maps), request);
  EXPECT_EQ(b.exhausted, 0u);
  EXPECT_GT(expect_same_samples_where_counts_agree(a, b), a.counts.size() * 9 / 10)
      << "counts and bounds agree for most triangles";
}

/// Quads over texel-aligned UV rectangles of a 16 x 16 map: every overlap is a dyadic fraction,
/// so both backends count them exactly and give every triangle the same N_T and D_T^max.
Mesh texel_aligned_quads(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Mesh m;
  for (int q = 0; q < count; ++q) {
    const float u0 = float(rng() % 12) / 16, v0 = float(rng() % 12) / 16;
    const float u1 = u0 + float(1 + rng() % 4) / 16, v1 = v0 + float(1 + rng() % 4) / 16;
    const float x = float(q), p[4][3] = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}};
    const float uv[4][2] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
    for (const auto& corners : {std::array{0, 1, 2}, std::array{0, 2, 3}}) {
      float tp[3][3], tuv[3][2];
      for (int k = 0; k < 3; ++k) {
        std::copy_n(p[corners[k]], 3, tp[k]);
        std::copy_n(uv[corners[k]], 2, tuv[k]);
      }
      m.add_triangle(tp, tuv);
    }
  }
  return m;
}

TEST_F(VulkanSampler, CandidateStreamIsTheCpusSampleForSample) {
  // The device's subgroups walk each segment together; the CPU walks it 16 candidates at a time.
  // Where both backends give every triangle the same N_T and D_T^max, the ordered scan puts
  // every sample in the same slot: the outputs are equal in order, with the same candidate,
  // exhausted and exact-draw counts, also when few tries per slot exhaust slots (or, for TRS,
  // stop the walk for exact draws) in the middle of a subgroup's round and carry rejections from
  // one round to the next. A sparse map keeps acceptance low.
  const Mesh mesh = texel_aligned_quads(40, 41);
  const std::vector<Map> maps = {trs_test::random_map(16, 16, 0.7, 42)};
  auto sampler = gpu(mesh, maps);
  struct Tries {
    std::uint32_t max_tries, exact_after;
  };
  for (const Tries tries : {Tries{1, 0}, Tries{2, 0}, Tries{5, 0}, Tries{1u << 28, 0}, Tries{1u << 28, 1},
                            Tries{1u << 28, 2}, Tries{3, 5}, Tries{1u << 28, 256}}) {
    SCOPED_TRACE(testing::Message() << "max_tries " << tries.max_tries << ", exact_after " << tries.exact_after);
    for (Method method : {Method::trs, Method::rejection}) {
      SCOPED_TRACE(to_string(method));
      const FrameRequest request{.seed = 3, .target_count = 50000, .method = method, .scan = ScanOrder::ordered,
                                 .max_tries = tries.max_tries, .exact_after = tries.exact_after};
      const Frame want = generate(*cpu(mesh, maps), request), got = generate(*sampler, request);
      if (method == Method::trs) {
        ASSERT_EQ(got.counts.size(), want.counts.size());
        for (std::size_t t = 0; t < want.counts.size(); ++t) {
          ASSERT_EQ(got.counts[t], want.counts[t]) << "triangle " << t;
          ASSERT_EQ(got.max_density[t], want.max_density[t]) << "triangle " << t;
        }
      }
      ASSERT_EQ(got.samples.size(), want.samples.size());
      expect_same_samples_in_order(want, got);
      EXPECT_EQ(got.candidates, want.candidates);
      EXPECT_EQ(got.exhausted, want.exhausted);
      EXPECT_EQ(got.exact_draws, want.exact_draws);
      const bool stops = method == Method::trs && tries.exact_after > 0;
      const std::uint32_t limit = stops ? std::min(tries.max_tries, tries.exact_after) : tries.max_tries;
      if (limit <= 2 && !stops) EXPECT_GT(want.exhausted, 0u);
      if (limit <= 2 && stops) EXPECT_GT(want.exact_draws, 0u);
    }
  }
}

TEST_F(VulkanSampler, ExactDrawsOfLargeTrianglesAreTheCpus) {
  // Exact draws walk a triangle's lattice cells a subgroup's width at a time: triangles of a few
  // to several hundred cells (within lavapipe's loop limit: device_exact_cells), over a sparse
  // map (dark cells are skipped before clipping), with wrap beyond the unit square, and a sliver:
  // one lit texel overlapped by 1e-6 of its triangle.
  Mesh mesh = trs_test::random_triangles(12, -0.3f, 1.3f, 61);
  const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const float corner = float((4.0 + 4e-3 / (1.0 - 1e-3)) / 16);  // the sliver of tests/sliver_test.cpp, on 16 texels
  const float uv[3][2] = {{0, 0}, {corner, 0}, {0, corner}};
  mesh.add_triangle(p, uv);
  // The sliver on a map of its own, scaled up to draw about half the samples.
  mesh.triangle_maps.assign(12, 0);
  mesh.triangle_maps.push_back(1);
  std::vector<Map> maps = {trs_test::random_map(16, 16, 0.9, 62), Map{std::vector<float>(16 * 16, 0.0f), 16, 16}};
  maps[1].texels[2 * 16 + 2] = 1.0f;
  maps[1].scale = 1e8f;
  auto sampler = gpu(mesh, maps);
  for (std::uint32_t exact_after : {1u, FrameRequest{}.exact_after}) {
    SCOPED_TRACE(exact_after);
    const FrameRequest request{.seed = 5, .target_count = 20000, .scan = ScanOrder::ordered, .exact_after = exact_after};
    const Frame want = generate(*cpu(mesh, maps), request), got = generate(*sampler, request);
    ASSERT_EQ(got.samples.size(), want.samples.size());
    expect_same_samples_in_order(want, got);
    EXPECT_EQ(got.candidates, want.candidates);
    EXPECT_EQ(got.exact_draws, want.exact_draws);
    EXPECT_GT(want.exact_draws, 0u);
    EXPECT_EQ(want.exhausted, 0u);
  }
}

TEST_F(VulkanSampler, FewSamplesOverManyTrianglesAreTheCpus) {
  // 200,000 triangles and 300 samples: a chunk of slots spans tens of thousands of triangles
  // without any, which the walk must pass by search (llvmpipe ends loops after 65,535 steps,
  // leaving slots unwritten).
  const Mesh mesh = texel_aligned_quads(100000, 43);
  const std::vector<Map> maps = {trs_test::random_map(16, 16, 0.0, 44)};
  const FrameRequest request{.seed = 4, .target_count = 300, .scan = ScanOrder::ordered};
  const Frame want = generate(*cpu(mesh, maps), request), got = generate(*gpu(mesh, maps), request);
  ASSERT_TRUE(std::ranges::equal(got.counts.span(), want.counts.span()));
  ASSERT_EQ(got.samples.size(), want.samples.size());
  expect_same_samples_in_order(want, got);
}

TEST_F(VulkanSampler, EveryAddressingAgreesExactlyWithTheCpuFarBeyondTheUnitSquare) {
  // Texel addresses of cells down to -40 on maps 7 and 5 texels wide: every counting path reads
  // exactly the CPU's texels (D_T^max equal, N-bar_T equal up to float summation order), and
  // realization draws the CPU's samples, bit for bit, wherever both gave a triangle the same
  // N_T; plain rejection sampling draws the CPU's samples in the CPU's order. GLSL leaves % of
  // a negative operand undefined; lavapipe happens to give C's remainder
  // where other drivers do not, so this test bites on GPUs.
  // Triangles a few texels across with UVs over [-5, 5]^2: most lattice cells they touch have
  // negative indices far from zero.
  const Mesh mesh = scattered_triangles(400, -4.8f, 4.8f, 0.2f, 21);
  for (Addressing addressing : {Addressing::wrap, Addressing::clamp, Addressing::mirror}) {
    SCOPED_TRACE(to_string(addressing));
    const std::vector<Map> maps = {distinct_map(7, 5, addressing)};
    const FrameRequest request{.seed = 9, .target_count = 2e5};
    const Frame reference = generate(*cpu(mesh, maps), request);
    auto sampler = gpu(mesh, maps);
    for (Counting path : {Counting::automatic, Counting::compute, Counting::raster, Counting::per_triangle}) {
      SCOPED_TRACE(to_string(path));
      FrameRequest r = request;
      r.vulkan.counting = path;
      const Frame f = generate(*sampler, r);
      ASSERT_EQ(f.max_density.size(), reference.max_density.size());
      // N-bar_T: the GPU counts on the float texel-space vertices the realization uses, the CPU on
      // UVs times the map size in double; around texel 35, slivers differ by up to 2e-3.
      for (std::size_t t = 0; t < f.max_density.size(); ++t) {
        ASSERT_EQ(f.max_density[t], reference.max_density[t]) << "triangle " << t;
        ASSERT_NEAR(f.expected_counts[t], reference.expected_counts[t], 4e-3 * reference.expected_counts[t])
            << "triangle " << t;
      }
      EXPECT_EQ(f.exhausted, 0u);
      EXPECT_GT(expect_same_samples_where_counts_agree(reference, f), reference.counts.size() * 95 / 100)
          << "N_T agree for most triangles";
    }
    // Plain rejection sampling reads the same texels through the same stream: the same samples.
    const FrameRequest rs{.seed = 9, .target_count = 2e4, .method = Method::rejection};
    const Frame want = generate(*cpu(mesh, maps), rs), got = generate(*sampler, rs);
    ASSERT_EQ(got.samples.size(), want.samples.size());
    expect_same_samples_in_order(want, got);
  }
}

TEST_F(VulkanSampler, RasterCountingRefusesTexelsBeyondFloatPrecision) {
  // UVs near 2.5e6 on an 8-texel map: texel 2e7, past 2^24, where the rasterizer's float
  // positions lose whole texels. Raster counting says so; compute counting is exact there.
  const float u = 2.5e6f;
  const Mesh mesh = trs_test::quad(1, 1, u, 0.0f, u + 0.5f, 0.5f);
  const std::vector<Map> maps = {distinct_map(8, 8, Addressing::wrap)};
  auto sampler = gpu(mesh, maps);
  EXPECT_THROW(generate(*sampler, {.realize = false, .vulkan = {.counting = Counting::raster}}), std::invalid_argument);
  const Frame reference = generate(*cpu(mesh, maps), {.realize = false});
  const Frame f = generate(*sampler, {.realize = false, .vulkan = {.counting = Counting::compute}});
  ASSERT_EQ(f.max_density.size(), reference.max_density.size());
  for (std::size_t t = 0; t < f.max_density.size(); ++t) EXPECT_EQ(f.max_density[t], reference.max_density[t]);
}

TEST_F(VulkanSampler, FramesWithoutATargetRealizeEverySample) {
  // A frame runs as one submission sized from a bound on N. Without a target the bound is the
  // last frame's N: the first frame (N about 1e5, far above the initial bound) runs again with
  // room, and a denser map later does too. Every frame still realizes all N samples, the CPU's
  // own wherever both backends gave a triangle the same N_T.
  const Mesh mesh = trs_test::random_triangles(200, 0.0f, 1.0f, 31);
  Map map = trs_test::random_map(32, 32, 0.3, 32);
  auto sampler = gpu(mesh, {map});
  for (float scale : {2000.0f, 2000.0f, 6000.0f}) {
    SCOPED_TRACE(scale);
    map.scale = scale;
    sampler->update_map(0, map.view());
    const Frame want = generate(*cpu(mesh, {map}), {.seed = 4});
    const Frame got = generate(*sampler, {.seed = 4});
    ASSERT_EQ(got.samples.size(), got.sample_count);
    EXPECT_NEAR(double(got.sample_count), want.expected_total, 5 * std::sqrt(want.expected_total));
    EXPECT_GT(expect_same_samples_where_counts_agree(want, got), want.counts.size() * 9 / 10);
  }
}

TEST_F(VulkanSampler, RejectionSamplingWithoutATargetDrawsTheCpuSamples) {
  // N is N-bar rounded, on the device from a float total (the CPU's is a double): the counts may
  // differ by one, and sample i, slot i of the output's candidate stream, is the same point on
  // both backends.
  const Mesh mesh = trs_test::random_triangles(100, 0.0f, 1.0f, 33);
  Map map = trs_test::random_map(16, 16, 0.3, 34);
  map.scale = 500.0f;
  const FrameRequest request{.seed = 6, .method = Method::rejection};
  const Frame want = generate(*cpu(mesh, {map}), request), got = generate(*gpu(mesh, {map}), request);
  ASSERT_GT(want.sample_count, 1000u);
  EXPECT_LE(std::max(want.sample_count, got.sample_count) - std::min(want.sample_count, got.sample_count), 1u);
  ASSERT_EQ(got.samples.size(), got.sample_count);
  expect_same_samples_in_order(want, got);
}

TEST_F(VulkanSampler, FrsDrawsTheCpuSamples) {
  // The same table (built on the host), the same stream and arithmetic: sample i is the CPU's,
  // with the same candidate and exhausted counts, also when few tries per slot exhaust slots.
  // The table is built by the first frame and again after update_map, timed as `distribution`.
  const Mesh mesh = trs_test::random_triangles(200, 0.0f, 1.0f, 51);
  std::vector<Map> maps = {trs_test::random_map(32, 32, 0.5, 52)};
  auto sampler = gpu(mesh, maps);
  auto has_distribution = [](const Frame& f) {
    return std::any_of(f.passes.begin(), f.passes.end(), [](const PassTime& p) { return p.pass == Pass::distribution; });
  };
  for (std::uint32_t max_tries : {1u << 28, 2u}) {
    SCOPED_TRACE(max_tries);
    const FrameRequest request{.seed = 7, .target_count = 1e5, .method = Method::frs, .max_tries = max_tries};
    const Frame want = generate(*cpu(mesh, maps), request), got = generate(*sampler, request);
    EXPECT_EQ(has_distribution(got), max_tries != 2u) << "built by the first frame only";
    EXPECT_EQ(got.setup_bytes, want.setup_bytes);
    EXPECT_EQ(got.expected_total, want.expected_total);
    ASSERT_EQ(got.sample_count, want.sample_count);
    ASSERT_EQ(got.samples.size(), want.samples.size());
    expect_same_samples_in_order(want, got);
    EXPECT_EQ(got.candidates, want.candidates);
    EXPECT_EQ(got.exhausted, want.exhausted);
    if (max_tries == 2u) EXPECT_GT(want.exhausted, 0u);
  }
  maps[0] = trs_test::random_map(16, 16, 0.3, 53);
  sampler->update_map(0, maps[0].view());
  const FrameRequest request{.seed = 8, .method = Method::frs};  // N-bar from the new table
  const Frame want = generate(*cpu(mesh, maps), request), got = generate(*sampler, request);
  EXPECT_TRUE(has_distribution(got));
  ASSERT_EQ(got.sample_count, want.sample_count);
  ASSERT_EQ(got.samples.size(), got.sample_count);
  expect_same_samples_in_order(want, got);
}

TEST_F(VulkanSampler, NaiveStratificationDrawsTheCpuSamples) {
  // The clipper's pieces and the stream of cpu/naive.cpp: where both backends give a triangle the
  // same N_T, its samples are the CPU's. On texel-aligned quads every count agrees and the
  // ordered scan puts every sample in the CPU's slot.
  const Mesh quads = texel_aligned_quads(40, 61);
  const std::vector<Map> quad_maps = {trs_test::random_map(16, 16, 0.5, 62)};
  const FrameRequest ordered{.seed = 3, .target_count = 50000, .method = Method::naive, .scan = ScanOrder::ordered};
  const Frame want = generate(*cpu(quads, quad_maps), ordered), got = generate(*gpu(quads, quad_maps), ordered);
  ASSERT_EQ(got.counts.size(), want.counts.size());
  for (std::size_t t = 0; t < want.counts.size(); ++t) ASSERT_EQ(got.counts[t], want.counts[t]) << "triangle " << t;
  ASSERT_EQ(got.samples.size(), want.samples.size());
  expect_same_samples_in_order(want, got);
  EXPECT_EQ(got.candidates, want.candidates);
  EXPECT_EQ(got.exhausted, want.exhausted);

  // Random triangles: N-bar_T by clipping agrees with the CPU's up to the float sum, D_T^max
  // exactly, and the samples wherever N_T agree.
  const Mesh mesh = trs_test::random_triangles(200, 0.0f, 1.0f, 63);
  const std::vector<Map> maps = {trs_test::random_map(16, 16, 0.3, 64)};
  const FrameRequest request{.seed = 5, .target_count = 3e4, .method = Method::naive};
  const Frame reference = generate(*cpu(mesh, maps), request);
  auto sampler = gpu(mesh, maps);
  const Frame f = generate(*sampler, request);
  EXPECT_EQ(f.counting_used, Counting::per_triangle);
  ASSERT_EQ(f.expected_counts.size(), reference.expected_counts.size());
  for (std::size_t t = 0; t < f.expected_counts.size(); ++t) {
    EXPECT_NEAR(f.expected_counts[t], reference.expected_counts[t], 1e-5 * reference.expected_counts[t]) << t;
    EXPECT_EQ(f.max_density[t], reference.max_density[t]) << t;
  }
  EXPECT_GT(expect_same_samples_where_counts_agree(reference, f), reference.counts.size() * 9 / 10);
  // Its counts are kept until a map changes, and are not TRS's.
  EXPECT_EQ(generate(*sampler, request).counting_used, std::nullopt);
  EXPECT_EQ(generate(*sampler, {.seed = 5, .target_count = 3e4}).counting_used, Counting::automatic);
  EXPECT_EQ(generate(*sampler, request).counting_used, Counting::per_triangle);
}

TEST_F(VulkanSampler, UnorderedScanIsAPermutation) {
  for (int triangles : {1, 255, 257, 1000, 70001}) {
    SCOPED_TRACE(triangles);
    const Mesh mesh = trs_test::random_triangles(triangles, 0.0f, 1.0f, std::uint64_t(triangles));
    const Frame f = generate(*gpu(mesh, {trs_test::random_map(16, 16, 0.5, 3)}),
                             {.target_count = 5.0 * triangles, .scan = ScanOrder::unordered, .realize = false});
    ASSERT_EQ(f.scan_used, ScanOrder::unordered);
    std::vector<char> seen(f.counts.size(), 0);
    std::uint64_t previous = 0;
    for (std::size_t p = 0; p < f.cdf.size(); ++p) {
      const std::uint32_t t = f.inverse_permutation[p];
      ASSERT_LT(t, f.counts.size());
      ASSERT_FALSE(seen[t]) << "triangle " << t << " twice";
      seen[t] = 1;
      ASSERT_EQ(f.cdf[p] - previous, f.counts[t]) << "processing index " << p;
      previous = f.cdf[p];
    }
    EXPECT_EQ(previous, f.sample_count);
  }
}

TEST_F(VulkanSampler, AutomaticScanFallsBackToOrderedWhenThePackedCounterWouldOverflow) {
  // Two triangles need 2 index bits, leaving 62 for the sum: 2^63 samples do not fit.
  auto sampler = gpu(trs_test::quad(1, 1, 0, 0, 1, 1), {Map{{1.0f}, 1, 1}});
  const Frame small = generate(*sampler, {.target_count = 1000, .realize = false});
  EXPECT_EQ(small.scan_used, ScanOrder::unordered);
  const Frame huge = generate(*sampler, {.target_count = 0x1p63, .realize = false});
  EXPECT_EQ(huge.scan_used, ScanOrder::ordered);
  EXPECT_EQ(huge.cdf[1], huge.sample_count);
  EXPECT_EQ(huge.cdf[0] + huge.counts[1], huge.cdf[1]);
  // Asked for explicitly: an error, never a silent overflow.
  EXPECT_THROW(generate(*sampler, {.target_count = 0x1p63, .scan = ScanOrder::unordered, .realize = false}),
               std::overflow_error);
}

TEST_F(VulkanSampler, OrderedScanIsThePrefixSum) {
  const Mesh mesh = trs_test::random_triangles(70001, 0.0f, 1.0f, 4);  // three scan levels
  const Frame f = generate(*gpu(mesh, {trs_test::random_map(16, 16, 0.5, 3)}),
                           {.target_count = 1e6, .scan = ScanOrder::ordered, .realize = false});
  std::uint64_t sum = 0;
  for (std::size_t t = 0; t < f.counts.size(); ++t) {
    sum += f.counts[t];
    ASSERT_EQ(f.cdf[t], sum) << "triangle " << t;
    ASSERT_EQ(f.inverse_permutation[t], t);
  }
}

/// Frames `a` and `b`, each from a sampler of its own, both alive until both frames are made: no
/// device memory (sampler buffers, or memory one of them freed) that `a` wrote can pass for
/// `b`'s outputs.
std::pair<Frame, Frame> separate_frames(const Mesh& mesh, const Map& map, const FrameRequest& a,
                                        const FrameRequest& b) {
  auto first = make_vulkan_sampler(mesh.view(), views({map}), {.validation = true});
  auto second = make_vulkan_sampler(mesh.view(), views({map}), {.validation = true});
  return {generate(*first, a), generate(*second, b)};
}

/// Per-triangle counting sums each N-bar_T in one invocation, and frames without a target round
/// each N-bar_T on its own: such frames of two samplers have the same N_T, and differ only in
/// what the request changes after counting.
constexpr Counting kExactCounting = Counting::per_triangle;

void expect_same_frame(const Frame& want, const Frame& got) {
  const auto values = [](const auto& buffer) { return std::vector(buffer.begin(), buffer.end()); };
  EXPECT_EQ(values(got.counts), values(want.counts));
  EXPECT_EQ(values(got.cdf), values(want.cdf));
  EXPECT_EQ(values(got.inverse_permutation), values(want.inverse_permutation));
  ASSERT_EQ(got.samples.size(), want.samples.size());
  expect_same_samples_in_order(want, got);
}

TEST_F(VulkanSampler, LookbackScanIsTheOrderedScanBitForBit) {
  // One triangle, a tile less one, several tiles; small triangles on a sparse map leave many
  // counts zero.
  for (int triangles : {1, int(gpu::kLookbackTile) - 1, 9 * int(gpu::kLookbackTile) + 17}) {
    SCOPED_TRACE(triangles);
    const Mesh mesh = scattered_triangles(triangles, 0.0f, 1.0f, 0.02f, std::uint64_t(triangles));
    Map map = trs_test::random_map(64, 64, 0.7, 21);
    map.scale = 40000.0f / float(triangles);
    const auto [ordered, got] =
        separate_frames(mesh, map, {.seed = 8, .scan = ScanOrder::ordered, .vulkan = {.counting = kExactCounting}},
                        {.seed = 8, .scan = ScanOrder::lookback, .vulkan = {.counting = kExactCounting}});
    EXPECT_EQ(got.scan_used, ScanOrder::lookback);
    if (triangles > 1) {
      ASSERT_GT(ordered.sample_count, 1000u);
      EXPECT_GT(std::count(ordered.counts.begin(), ordered.counts.end(), 0u), 0) << "some counts are zero";
    }
    expect_same_frame(ordered, got);
  }
}

TEST_F(VulkanSampler, LookbackScanRefusesTotalsOf2To62) {
  auto sampler = gpu(trs_test::quad(1, 1, 0, 0, 1, 1), {Map{{1.0f}, 1, 1}});
  EXPECT_THROW(generate(*sampler, {.target_count = 0x1p62, .scan = ScanOrder::lookback, .realize = false}),
               std::overflow_error);
}

TEST_F(VulkanSampler, InverseCdfDrawsTheSameSamples) {
  const Mesh mesh = scattered_triangles(3000, 0.0f, 1.0f, 0.02f, 23);
  Map map = trs_test::random_map(64, 64, 0.5, 24);
  map.scale = 60.0f;
  for (ScanOrder scan : {ScanOrder::ordered, ScanOrder::lookback}) {
    SCOPED_TRACE(to_string(scan));
    const auto [plain, guided] =
        separate_frames(mesh, map, {.seed = 9, .scan = scan, .vulkan = {.counting = kExactCounting}},
                        {.seed = 9, .scan = scan, .vulkan = {.counting = kExactCounting, .inverse_cdf = true}});
    ASSERT_GT(plain.sample_count, 10000u);
    expect_same_frame(plain, guided);
  }
}

TEST_F(VulkanSampler, WithoutSubgroupReductionTheCountsAndSamplesAgree) {
  // Counting sums floats in another order: N-bar_T within the counting tolerance, the same
  // samples where N_T agrees. The unordered scan reserves its slots lane by lane.
  const Mesh mesh = trs_test::random_triangles(300, 0.0f, 1.0f, 25);
  Map map = trs_test::random_map(32, 32, 0.3, 26);
  map.scale = 200.0f;
  for (Counting path : {Counting::raster, Counting::compute}) {
    SCOPED_TRACE(to_string(path));
    const FrameRequest request{.seed = 10, .scan = ScanOrder::unordered, .vulkan = {.counting = path}};
    FrameRequest ablation = request;
    ablation.vulkan.subgroup_reduction = false;
    const auto [reduced, got] = separate_frames(mesh, map, request, ablation);
    EXPECT_EQ(got.counting_used, path);
    ASSERT_GT(reduced.sample_count, 10000u);
    double largest = 0;
    for (double e : reduced.expected_counts) largest = std::max(largest, e);
    for (std::size_t t = 0; t < got.expected_counts.size(); ++t) {
      const double want = reduced.expected_counts[t];
      EXPECT_NEAR(got.expected_counts[t], want, 1e-4 * std::max(want, 1e-3 * largest)) << "triangle " << t;
      EXPECT_EQ(got.max_density[t], reduced.max_density[t]) << "triangle " << t;
    }
    EXPECT_NEAR(got.expected_total, reduced.expected_total, 1e-4 * reduced.expected_total);
    ASSERT_EQ(got.scan_used, ScanOrder::unordered);
    std::vector<char> seen(got.counts.size(), 0);
    std::uint64_t previous = 0;
    for (std::size_t p = 0; p < got.cdf.size(); ++p) {
      const std::uint32_t t = got.inverse_permutation[p];
      ASSERT_FALSE(seen[t]) << "triangle " << t << " twice";
      seen[t] = 1;
      ASSERT_EQ(got.cdf[p] - previous, got.counts[t]) << "processing index " << p;
      previous = got.cdf[p];
    }
    EXPECT_EQ(previous, got.sample_count);
    EXPECT_GT(expect_same_samples_where_counts_agree(reduced, got), got.counts.size() * 9 / 10);
  }
}

TEST_F(VulkanSampler, OutputsBeyond128MiBAnd65535Workgroups) {
  // 17 million samples: 204 MB of output, and the work of more than 65535 workgroups of 256.
  const Mesh mesh = trs_test::quad(2, 1, 0, 0, 1, 1);
  const std::vector<Map> maps = {trs_test::random_map(64, 32, 0.5, 14)};
  auto sampler = gpu(mesh, maps);
  const Frame f = generate(*sampler, {.seed = 3, .target_count = 17e6});
  ASSERT_EQ(f.samples.size(), f.sample_count);
  EXPECT_GT(f.sample_count * sizeof(Sample), std::uint64_t(128) << 20);
  EXPECT_GT(f.sample_count, 65535ull * 256);
  std::uint64_t bad = 0;
  for (const Sample& s : f.samples)
    bad += !(s.triangle < 2 && s.b1 >= 0 && s.b2 >= 0 && s.b1 + s.b2 <= 1 && sampler->maps().density(s.triangle, s.b1, s.b2) > 0);
  EXPECT_EQ(bad, 0u);
}

TEST_F(VulkanSampler, AllZeroMapGivesNoSamples) {
  auto sampler = gpu(trs_test::quad(1, 1, 0, 0, 1, 1), {Map{std::vector<float>(16, 0.0f), 4, 4}});
  for (Method method : {Method::trs, Method::rejection}) {
    const Frame f = generate(*sampler, {.target_count = 1e5, .method = method});
    EXPECT_EQ(f.sample_count, 0u) << to_string(method);
    EXPECT_TRUE(f.samples.empty());
  }
}

TEST_F(VulkanSampler, UpdatedMapChangesTheNextFrame) {
  const Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const Map left{{1.0f, 0.0f}, 2, 1}, right{{0.0f, 1.0f, 0.0f, 1.0f}, 2, 2};
  auto sampler = gpu(mesh, {left});
  for (const Sample& s : generate(*sampler, {.seed = 1, .target_count = 5000}).samples)
    ASSERT_LT(lightsampler::uv(mesh.view(), s).x, 0.5f);
  sampler->update_map(0, right.view());  // a new size too
  for (const Sample& s : generate(*sampler, {.seed = 2, .target_count = 5000}).samples)
    ASSERT_GE(lightsampler::uv(mesh.view(), s).x, 0.5f);
  const Map right_same_size{{0.0f, 2.0f}, 2, 1};
  sampler->update_map(0, right_same_size.view());  // in place
  for (const Sample& s : generate(*sampler, {.seed = 3, .target_count = 5000}).samples)
    ASSERT_GE(lightsampler::uv(mesh.view(), s).x, 0.5f);
}

TEST_F(VulkanSampler, CountsAreKeptUntilAMapChanges) {
  // N-bar_T and D_T^max stay on the device between frames: a frame counts nothing until
  // update_map (or another counting path), and then counts the triangles of the replaced map
  // alone, as a new sampler over the new maps does.
  Mesh mesh = trs_test::random_triangles(300, 0.0f, 1.0f, 41);
  for (std::uint32_t t = 0; t < 300; ++t) mesh.triangle_maps.push_back(t % 7 == 0 ? kNoMap : t % 2);
  std::vector<Map> maps = {trs_test::random_map(32, 32, 0.5, 42), trs_test::random_map(16, 16, 0.5, 44)};
  auto sampler = gpu(mesh, maps);
  const Frame first = generate(*sampler, {.seed = 1, .target_count = 1e5});
  EXPECT_EQ(first.counting_used, Counting::automatic);
  const Frame kept = generate(*sampler, {.seed = 2, .target_count = 1e5});
  EXPECT_EQ(kept.counting_used, std::nullopt);
  EXPECT_EQ(kept.expected_total, first.expected_total);
  for (std::size_t t = 0; t < first.counts.size(); ++t)
    ASSERT_TRUE(kept.expected_counts[t] == first.expected_counts[t] && kept.max_density[t] == first.max_density[t]);
  EXPECT_EQ(generate(*sampler, {.seed = 2, .target_count = 1e5, .vulkan = {.counting = Counting::per_triangle}})
                .counting_used,
            Counting::per_triangle);
  EXPECT_EQ(generate(*sampler, {.seed = 2, .target_count = 1e5}).counting_used, Counting::automatic);

  maps[1] = trs_test::random_map(24, 24, 0.2, 43);  // a new size too
  sampler->update_map(1, maps[1].view());
  const Frame updated = generate(*sampler, {.seed = 3, .target_count = 1e5});
  EXPECT_EQ(updated.counting_used, Counting::automatic);
  const Frame fresh = generate(*gpu(mesh, maps), {.seed = 3, .target_count = 1e5});
  for (std::size_t t = 0; t < fresh.counts.size(); ++t) {
    if (mesh.triangle_maps[t] == 0)  // not counted again: as it was
      ASSERT_TRUE(updated.expected_counts[t] == first.expected_counts[t] &&
                  updated.max_density[t] == first.max_density[t]) << t;
    ASSERT_NEAR(updated.expected_counts[t], fresh.expected_counts[t], 1e-5 * fresh.expected_counts[t]) << t;
    ASSERT_EQ(updated.max_density[t], fresh.max_density[t]) << t;
  }
  EXPECT_GT(expect_same_samples_where_counts_agree(fresh, updated), fresh.counts.size() * 9 / 10);
}

TEST_F(VulkanSampler, TheWriteFloorIsAGpuTime) {
  // 17 million samples: the kernel's grid-stride loop covers more than 65535 workgroups' worth.
  const double ms = sample_write_ms(Backend::vulkan, {.vulkan = {.validation = true}}, 17'000'000, 2);
  EXPECT_TRUE(std::isfinite(ms) && ms > 0) << ms;
}

TEST_F(VulkanSampler, ReportsTheDeviceAndPerPassTimes) {
  auto sampler = gpu(trs_test::quad(1, 1, 0, 0, 1, 1), {Map{{1.0f, 2.0f}, 2, 1}});
  EXPECT_EQ(sampler->backend(), Backend::vulkan);
  EXPECT_FALSE(sampler->device().empty());
  const Frame f = generate(*sampler, {.target_count = 1000});
  std::vector<Pass> passes;
  for (const PassTime& p : f.passes) {
    passes.push_back(p.pass);
    EXPECT_GE(p.ms, 0.0) << to_string(p.pass);
  }
  EXPECT_EQ(passes, (std::vector<Pass>{Pass::counting, Pass::rounding, Pass::scan, Pass::realization, Pass::readback}));
  passes.clear();
  for (const PassTime& p : generate(*sampler, {.target_count = 1000, .method = Method::frs}).passes) passes.push_back(p.pass);
  EXPECT_EQ(passes, (std::vector<Pass>{Pass::distribution, Pass::realization, Pass::readback}));
}
