// Defined behaviour on degenerate and bad input (DESIGN.md, "Degenerate input").

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "lightsampler/sampler.h"
#include "sampler_fixtures.h"
#include "same_frame.h"
#include "core/validate.h"

using namespace lightsampler;
using trs_test::Map;
using trs_test::Mesh;

namespace {

Frame run(const Mesh& mesh, const std::vector<Map>& maps, FrameRequest request = {},
          CpuOptions options = {}) {
  std::vector<DensityMapView> views;
  for (const Map& m : maps) views.push_back(m.view());
  auto sampler = make_cpu_sampler(mesh.view(), views, options);
  Frame frame;
  sampler->generate(request, frame);
  return frame;
}

std::string error_of(const Mesh& mesh, const std::vector<Map>& maps) {
  std::vector<DensityMapView> views;
  for (const Map& m : maps) views.push_back(m.view());
  try {
    make_cpu_sampler(mesh.view(), views);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

FrameRequest target(double n, std::uint64_t seed = 0) {
  FrameRequest r;
  r.target_count = n;
  r.seed = seed;
  return r;
}

}  // namespace

TEST(EdgeCases, ZeroWorldAreaTriangleGetsNoSamples) {
  Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const float flat[3][3] = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};  // collinear in world space
  const float uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  mesh.add_triangle(flat, uv);
  const Frame f = run(mesh, {Map{{1.0f}, 1, 1}}, target(1000));
  EXPECT_EQ(f.expected_counts[2], 0.0);
  EXPECT_EQ(f.counts[2], 0u);
  for (const Sample& s : f.samples) EXPECT_NE(s.triangle, 2u);
}

TEST(EdgeCases, ZeroUvAreaTriangleHasTheDensityOfItsUvPoint) {
  // All three UVs on one point (a mesh exported without UVs): constant density, that texel's.
  Mesh mesh;
  const float p[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};  // world area 3
  const float uv[3][2] = {{0.6f, 0.1f}, {0.6f, 0.1f}, {0.6f, 0.1f}};
  mesh.add_triangle(p, uv);
  const Map map{{1, 2, 5, 7}, 4, 1};  // u = 0.6 reads texel 2
  const Frame f = run(mesh, {map}, target(500));
  EXPECT_NEAR(f.expected_total, 15.0, 1e-5);
  EXPECT_EQ(f.max_density[0], 5.0f);
  EXPECT_EQ(f.candidates, f.sample_count) << "constant density: every candidate is accepted";
}

TEST(EdgeCases, InvalidTexelsAreRejectedNamingTheTexel) {
  const Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  for (auto [value, word] : {std::tuple{std::numeric_limits<float>::quiet_NaN(), "NaN"},
                             std::tuple{-1.0f, "negative"},
                             std::tuple{std::numeric_limits<float>::infinity(), "infinite"}}) {
    Map map{std::vector<float>(6, 1.0f), 3, 2};
    map.texels[4] = value;  // texel (1, 1)
    const std::string message = error_of(mesh, {map});
    EXPECT_NE(message.find("density map 0: texel (1, 1)"), std::string::npos) << message;
    EXPECT_NE(message.find(word), std::string::npos) << message;
  }
}

TEST(EdgeCases, WrapReadsTheSameTexelsOneTileAway) {
  const Map map = trs_test::random_map(8, 8, 0.2, 1);
  const Frame inside = run(trs_test::quad(1, 1, 0.1f, 0.2f, 0.7f, 0.9f), {map}, {.realize = false});
  const Frame shifted = run(trs_test::quad(1, 1, 2.1f, -0.8f, 2.7f, -0.1f), {map}, {.realize = false});
  EXPECT_NEAR(inside.expected_total, shifted.expected_total, 1e-6 * inside.expected_total);
}

TEST(EdgeCases, ClampReadsTheBorderTexelBeyondTheMap) {
  Map map{{1, 2, 3, 4}, 2, 2};
  map.addressing = Addressing::clamp;
  // UVs in [1.5, 3]^2 read texel (1, 1) = 4 everywhere: N-bar = 4 * area 2.
  const Frame f = run(trs_test::quad(2, 1, 1.5f, 1.5f, 3, 3), {map}, target(100));
  EXPECT_NEAR(f.expected_total, 8.0, 1e-9);
  EXPECT_EQ(f.candidates, f.sample_count);
}

// texel() names the texel density() reads, after addressing: a renderer reads its own data there.
TEST(EdgeCases, TexelIsTheOneDensityReads) {
  Map map = trs_test::random_map(5, 3, 0.3, 7);
  map.scale = 2.0f;
  Mesh mesh = trs_test::random_triangles(50, -1.5f, 2.5f, 11);
  mesh.triangle_maps.assign(50, 0);
  mesh.triangle_maps[3] = kNoMap;
  const auto sampler = make_cpu_sampler(mesh.view(), std::vector{map.view()});
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::uint32_t t = 0; t < 50; ++t) {
    for (int i = 0; i < 20; ++i) {
      float b1 = u(rng), b2 = u(rng);
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      const std::optional<Texel> texel = sampler->maps().texel(t, b1, b2);
      if (t == 3) {
        EXPECT_FALSE(texel.has_value());
        continue;
      }
      ASSERT_TRUE(texel.has_value());
      ASSERT_LT(texel->x, map.width);
      ASSERT_LT(texel->y, map.height);
      EXPECT_EQ(texel->map, 0u);
      EXPECT_EQ(sampler->maps().density(t, b1, b2), map.texels[texel->y * map.width + texel->x] * 2.0f);
    }
  }
}

TEST(EdgeCases, AllZeroMapGivesNoSamplesWithOrWithoutTarget) {
  const Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const Map zero{std::vector<float>(16, 0.0f), 4, 4};
  for (Method method : {Method::trs, Method::rejection, Method::naive, Method::frs}) {
    for (FrameRequest request : {FrameRequest{}, target(1e6)}) {
      request.method = method;
      const Frame f = run(mesh, {zero}, request);
      EXPECT_EQ(f.sample_count, 0u) << to_string(method);
      EXPECT_TRUE(f.samples.empty());
    }
  }
}

TEST(EdgeCases, SingleTexelMapIsUniform) {
  const Frame f = run(trs_test::quad(2, 2, 0, 0, 1, 1), {Map{{3.0f}, 1, 1}}, target(1000));
  EXPECT_NEAR(f.expected_total, 12.0, 1e-9);
  EXPECT_EQ(f.candidates, f.sample_count);
}

TEST(EdgeCases, MeshWithoutMapsHasZeroDensity) {
  const Frame none = run(trs_test::quad(1, 1, 0, 0, 1, 1), {}, target(100));
  EXPECT_EQ(none.expected_total, 0.0);
  EXPECT_EQ(none.sample_count, 0u);

  Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  mesh.triangle_maps = {kNoMap, 0};  // only the second triangle has a map
  const Frame half = run(mesh, {Map{{1.0f}, 1, 1}}, target(100));
  EXPECT_EQ(half.counts[0], 0u);
  EXPECT_EQ(half.counts[1], 100u);
}

TEST(EdgeCases, SeveralMapsOneSampler) {
  Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  mesh.triangle_maps = {1, 0};
  const Frame f = run(mesh, {Map{{1.0f}, 1, 1}, Map{{3.0f}, 1, 1}}, {.realize = false});
  EXPECT_NEAR(f.expected_counts[0], 1.5, 1e-12);
  EXPECT_NEAR(f.expected_counts[1], 0.5, 1e-12);
}

TEST(EdgeCases, BadMeshesAreRejectedWithWhatAndWhere) {
  Mesh bad_index = trs_test::quad(1, 1, 0, 0, 1, 1);
  bad_index.indices[4] = 9;
  EXPECT_NE(error_of(bad_index, {}).find("triangle 1 uses vertex 9"), std::string::npos);

  Mesh bad_map = trs_test::quad(1, 1, 0, 0, 1, 1);
  bad_map.triangle_maps = {0, 3};
  EXPECT_NE(error_of(bad_map, {Map{{1.0f}, 1, 1}}).find("triangle 1 uses density map 3"), std::string::npos);

  Mesh nan_uv = trs_test::quad(1, 1, 0, 0, 1, 1);
  nan_uv.uvs[5] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(error_of(nan_uv, {}).find("uv of vertex 2 is not finite"), std::string::npos);

  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    Mesh bad_position = trs_test::quad(1, 1, 0, 0, 1, 1);
    bad_position.positions[10] = bad;
    EXPECT_NE(error_of(bad_position, {}).find("position of vertex 3 is not finite"), std::string::npos);
  }

  Mesh short_uvs = trs_test::quad(1, 1, 0, 0, 1, 1);
  short_uvs.uvs.resize(6);
  EXPECT_NE(error_of(short_uvs, {}).find("4 positions but 3 uvs"), std::string::npos);

  EXPECT_NE(error_of(trs_test::quad(1, 1, 0, 0, 1, 1), {Map{{1.0f, 2.0f}, 3, 1}}).find("2 texels for 3x1"),
            std::string::npos);
}

TEST(EdgeCases, TwoToThe32TrianglesAreRefused) {
  EXPECT_NO_THROW(core::validate_triangle_count(0xffffffffull));
  EXPECT_THROW(core::validate_triangle_count(0x100000000ull), std::length_error);
}

TEST(EdgeCases, BadTargetsAreRejected) {
  const Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), 1e30})
    EXPECT_THROW(run(mesh, {Map{{1.0f}, 1, 1}}, target(bad)), std::invalid_argument);
}

TEST(EdgeCases, ExhaustedSamplesAreCountedAndExactDrawsTakeThem) {
  // One bright texel among zeros: with a single try most samples cannot be accepted. Under the
  // paper's rule (exact_after 0) they give up; with exact draws after the first rejection none
  // does, and every sample lies in the bright texel.
  Map map{std::vector<float>(64, 0.0f), 8, 8};
  map.texels[9] = 1.0f;
  const Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const DensityMapView view = map.view();
  auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
  for (std::uint32_t exact_after : {0u, 1u}) {
    SCOPED_TRACE(exact_after);
    FrameRequest request = target(1000);
    request.max_tries = 1;
    request.exact_after = exact_after;
    Frame f;
    sampler->generate(request, f);
    if (exact_after == 0) {
      EXPECT_GT(f.exhausted, 0u);
      EXPECT_EQ(f.exact_draws, 0u);
      EXPECT_EQ(f.candidates, f.sample_count) << "exactly one try each";
    } else {
      EXPECT_EQ(f.exhausted, 0u);
      EXPECT_GT(f.exact_draws, f.sample_count / 2);
      for (const Sample& s : f.samples) ASSERT_GT(sampler->maps().density(s.triangle, s.b1, s.b2), 0.0f);
    }
  }
}

TEST(EdgeCases, UpdatedMapChangesTheNextFrame) {
  const Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const Map left{{1.0f, 0.0f}, 2, 1}, right{{0.0f, 1.0f, 0.0f, 1.0f}, 2, 2};
  const DensityMapView view = left.view();
  auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
  Frame frame;
  sampler->generate(target(2000, 1), frame);
  for (const Sample& s : frame.samples) ASSERT_LT(lightsampler::uv(mesh.view(), s).x, 0.5f);
  EXPECT_EQ(sampler->maps().density(0, 0.0f, 0.0f), 1.0f);  // vertex 0 at uv (0, 0)

  sampler->update_map(0, right.view());  // a new size too
  sampler->generate(target(2000, 2), frame);
  for (const Sample& s : frame.samples) ASSERT_GE(lightsampler::uv(mesh.view(), s).x, 0.5f);
  EXPECT_EQ(sampler->maps().density(0, 0.0f, 0.0f), 0.0f);
  EXPECT_THROW(sampler->update_map(1, right.view()), std::out_of_range);
}

TEST(EdgeCases, CountsAreKeptUntilAMapChangesThenRecountedAsNew) {
  // N-bar_T and D_T^max change only with a map: frames count nothing until update_map, then
  // recount the triangles of that map alone. The frame is then the one a new sampler over the
  // new maps gives, bit for bit.
  Mesh mesh = trs_test::random_triangles(300, 0.0f, 1.0f, 5);
  for (std::uint32_t t = 0; t < 300; ++t) mesh.triangle_maps.push_back(t % 7 == 0 ? kNoMap : t % 2);
  std::vector<Map> maps = {trs_test::random_map(32, 32, 0.5, 6), trs_test::random_map(16, 16, 0.5, 7)};
  const std::vector<DensityMapView> views = {maps[0].view(), maps[1].view()};
  auto sampler = make_cpu_sampler(mesh.view(), views);
  Frame frame;
  sampler->generate(target(1e5, 1), frame);
  EXPECT_EQ(frame.counting_used, Counting::cpu);
  const std::vector<double> first(frame.expected_counts.span().begin(), frame.expected_counts.span().end());
  sampler->generate(target(1e5, 2), frame);
  EXPECT_EQ(frame.counting_used, std::nullopt);
  EXPECT_TRUE(std::equal(first.begin(), first.end(), frame.expected_counts.span().begin()));

  for (const auto& [index, map] : {std::pair{1, trs_test::random_map(24, 24, 0.5, 8)},     // a new size
                                   std::pair{0, trs_test::random_map(32, 32, 0.2, 9)}}) {  // in place
    maps[std::size_t(index)] = map;
    sampler->update_map(std::size_t(index), maps[std::size_t(index)].view());
    sampler->generate(target(1e5, 3), frame);
    EXPECT_EQ(frame.counting_used, Counting::cpu);
    trs_test::expect_same_frames(frame, run(mesh, maps, target(1e5, 3)));
  }
}

TEST(EdgeCases, FramesOnOneSamplerCountAnewWhenTheCountingRuleChanges) {
  // Naive stratification keeps its counts like TRS, but its clipped counts are not the closed
  // form's, nor are those of Eq. 6's overlaps: a change of method or of overlap formula counts
  // anew, and each frame is what a new sampler gives.
  const Mesh mesh = trs_test::random_triangles(200, 0.0f, 1.0f, 15);
  const std::vector<Map> maps = {trs_test::random_map(24, 24, 0.5, 16)};
  const DensityMapView view = maps[0].view();
  auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
  FrameRequest naive = target(1e4, 2), sdf = target(1e4, 4), clipping = target(1e4, 5);
  naive.method = Method::naive;
  sdf.overlap = Overlap::sdf;
  clipping.overlap = Overlap::clipping;
  const auto rule = [](const FrameRequest& r) { return std::pair(r.method, r.overlap); };
  std::optional<std::pair<Method, Overlap>> counted;
  Frame frame;
  for (const FrameRequest& request : {target(1e4, 1), naive, naive, target(1e4, 3), sdf, sdf, clipping, target(1e4, 6)}) {
    sampler->generate(request, frame);
    EXPECT_EQ(frame.counting_used.has_value(), counted != rule(request))
        << to_string(request.method) << ", " << to_string(request.overlap);
    counted = rule(request);
    trs_test::expect_same_frames(frame, run(mesh, maps, request));
  }
}

TEST(EdgeCases, FastRejectionSamplingBuildsOnceAndAgainAfterAMapChanges) {
  // The subdivision is FRS's set-up: timed as the `distribution` pass of the frame that builds
  // it, and redone after update_map, when the frame is the one a new sampler gives.
  const Mesh mesh = trs_test::random_triangles(100, 0.0f, 1.0f, 25);
  std::vector<Map> maps = {trs_test::random_map(32, 32, 0.5, 26)};
  DensityMapView view = maps[0].view();
  auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
  const auto built = [](const Frame& f) {
    return std::any_of(f.passes.begin(), f.passes.end(), [](const PassTime& p) { return p.pass == Pass::distribution; });
  };
  FrameRequest frs = target(1e4, 1);
  frs.method = Method::frs;
  Frame frame;
  for (int f = 0; f < 2; ++f) {
    sampler->generate(frs, frame);
    EXPECT_EQ(built(frame), f == 0);
    EXPECT_GT(frame.setup_bytes, 0u);
  }
  maps[0] = trs_test::random_map(32, 32, 0.2, 27);
  view = maps[0].view();
  sampler->update_map(0, view);
  sampler->generate(frs, frame);
  EXPECT_TRUE(built(frame));
  trs_test::expect_same_frames(frame, run(mesh, maps, frs));
}

TEST(EdgeCases, SameSeedSameSamplesOnAnyThreadCount) {
  const Mesh mesh = trs_test::random_triangles(500, 0.0f, 1.0f, 3);
  const Map map = trs_test::random_map(64, 64, 0.5, 4);
  for (Method method : {Method::trs, Method::naive, Method::frs}) {
    auto sorted_samples = [&](unsigned threads, ScanOrder scan) {
      FrameRequest request = target(200000, 42);
      request.scan = scan;
      request.method = method;
      const Frame f = run(mesh, {map}, request, {threads});
      std::vector<std::tuple<std::uint32_t, float, float>> v;
      for (const Sample& s : f.samples) v.emplace_back(s.triangle, s.b1, s.b2);
      return v;
    };
    auto ordered = sorted_samples(1, ScanOrder::ordered);
    // The ordered scan fixes the output order: identical arrays.
    EXPECT_EQ(ordered, sorted_samples(2, ScanOrder::ordered)) << to_string(method);
    // The unordered scan permutes triangles' blocks, never the set of samples.
    auto unordered = sorted_samples(2, ScanOrder::unordered);
    std::sort(ordered.begin(), ordered.end());
    std::sort(unordered.begin(), unordered.end());
    EXPECT_EQ(ordered, unordered) << to_string(method);
  }
}

TEST(EdgeCases, SampleHelpersReadTheMesh) {
  const Mesh mesh = trs_test::quad(2, 4, 0, 0, 1, 1);
  const Sample s{1, 0.25f, 0.5f};  // triangle (v0, v2, v3)
  const Float3 p = position(mesh.view(), s);
  EXPECT_FLOAT_EQ(p.x, 0.5f);
  EXPECT_FLOAT_EQ(p.y, 3.0f);
  const Float2 t = lightsampler::uv(mesh.view(), s);
  EXPECT_FLOAT_EQ(t.x, 0.25f);
  EXPECT_FLOAT_EQ(t.y, 0.75f);
  const Float3 n = geometric_normal(mesh.view(), s);
  EXPECT_FLOAT_EQ(n.z, 1.0f);
}
