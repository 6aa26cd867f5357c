// Are the samples distributed in proportion to the density? Chi-square goodness of fit over
// (triangle, texel) cells, with expected counts computed independently of the sampler (polygon
// clipping, texel by texel: tests/support/polygon_clip.h).
//
// Hypothesis H0: the sampler draws from the density. Fixed seeds; significance
// trs_test::kDistributionAlpha per test; cells with expectation under 5 pooled; any sample in a
// zero-probability cell fails. Each test is shown to reject a deliberately wrong sampler.

#include <gtest/gtest.h>

#include <cmath>

#include "cpu/frs.h"
#include "cpu/passes.h"
#include "distribution_check.h"
#include "lightsampler/triangle_map.h"

using namespace lightsampler;
using trs_test::Scenario;

namespace {

const double kAlpha = trs_test::kDistributionAlpha;

Frame generate(const Scenario& s, Method method, Overlap overlap = Overlap::closed_form,
               std::uint32_t exact_after = FrameRequest{}.exact_after) {
  const DensityMapView view = s.map.view();
  auto sampler = make_cpu_sampler(s.mesh.view(), {&view, 1});
  Frame frame;
  sampler->generate(
      {.seed = s.seed, .target_count = s.target, .method = method, .overlap = overlap, .exact_after = exact_after},
      frame);
  for (const Sample& x : frame.samples)
    EXPECT_GT(sampler->maps().density(x.triangle, x.b1, x.b2), 0.0f) << "a sample where the density is zero";
  return frame;
}

/// A wrong realization: the sqrt-free map misused (b2 = u1 (1 - u0) is not uniform on the
/// triangle: it crowds vertex 1).
void realize_with_wrong_map(const Scenario& s, const Frame& counted, Buffer<Sample>& samples) {
  const auto tris = trs_test::texel_triangles(s);
  const core::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  const PhiloxKey key = stream_key(s.seed, Stream::realization);
  samples.resize(counted.sample_count);
  std::uint64_t i = 0;
  for (std::size_t p = 0; p < counted.cdf.size(); ++p) {
    const std::uint32_t tri = counted.inverse_permutation[p];
    for (std::uint64_t rank = 0; rank < counted.counts[tri]; ++rank, ++i)
      for (std::uint32_t attempt = 0;; ++attempt) {
        const PhiloxCounter u = philox4x32({tri, std::uint32_t(rank), 0, attempt}, key);
        const float u0 = uniform_float(u[0]), u1 = uniform_float(u[1]);
        const Sample x{tri, u0, u1 * (1 - u0)};
        if (uniform_float(u[2]) * counted.max_density[tri] <
            core::texel_triangle_density(tris[tri], {&map, 1}, x.b1, x.b2)) {
          samples[i] = x;
          break;
        }
      }
  }
}

}  // namespace

TEST(Distribution, TrsMatchesTheDensity) {
  for (const Scenario& s : trs_test::scenarios()) {
    const Frame frame = generate(s, Method::trs);
    const auto result = trs_test::test_per_triangle(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name << ": too few cells to have power";
    EXPECT_TRUE(result.passes(kAlpha)) << s.name << "\n" << result.describe();
  }
}

// TRS that gives up rejection at the first rejection in a row: most slots are exact draws from
// the triangles' texel pieces, and the samples still follow the density.
TEST(Distribution, TrsWithExactDrawsMatchesTheDensity) {
  for (const Scenario& s : trs_test::scenarios()) {
    const Frame frame = generate(s, Method::trs, Overlap::closed_form, 1);
    EXPECT_GT(frame.exact_draws, frame.sample_count / 4) << s.name << ": exact draws are exercised";
    EXPECT_EQ(frame.exhausted, 0u) << s.name;
    const auto result = trs_test::test_per_triangle(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name << ": too few cells to have power";
    EXPECT_TRUE(result.passes(kAlpha)) << s.name << "\n" << result.describe();
  }
}

TEST(Distribution, RejectionSamplingMatchesTheDensity) {
  for (const Scenario& s : trs_test::scenarios()) {
    const Frame frame = generate(s, Method::rejection);
    const auto result = trs_test::test_all_cells(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name;
    EXPECT_TRUE(result.passes(kAlpha)) << s.name << "\n" << result.describe();
  }
}

TEST(Distribution, NaiveStratificationMatchesTheDensity) {
  for (const Scenario& s : trs_test::scenarios()) {
    const Frame frame = generate(s, Method::naive);
    EXPECT_EQ(frame.exhausted, 0u) << s.name;
    const auto result = trs_test::test_per_triangle(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name << ": too few cells to have power";
    EXPECT_TRUE(result.passes(kAlpha)) << s.name << "\n" << result.describe();
  }
}

// Naive stratification counts by clipping what TRS counts by its closed form: the same N-bar_T
// and D_T^max, up to rounding (it clips the realization's float texel-space triangle, the
// closed form works from the UVs in double: a relative 1e-7 apart).
TEST(Distribution, NaiveAndTrsCountTheSame) {
  for (const Scenario& s : trs_test::scenarios()) {
    const Frame trs = generate(s, Method::trs), naive = generate(s, Method::naive);
    ASSERT_EQ(trs.expected_counts.size(), naive.expected_counts.size());
    for (std::size_t t = 0; t < trs.expected_counts.size(); ++t) {
      EXPECT_NEAR(naive.expected_counts[t], trs.expected_counts[t], 1e-6 * (1.0 + trs.expected_counts[t]))
          << s.name << ", triangle " << t;
      EXPECT_EQ(naive.max_density[t], trs.max_density[t]) << s.name << ", triangle " << t;
    }
  }
}

// Counting by polygon clipping (Overlap::clipping) gives what the closed form gives, up to rounding.
TEST(Distribution, ClippingOverlapCountsAsTheClosedForm) {
  for (const Scenario& s : trs_test::scenarios()) {
    const Frame closed = generate(s, Method::trs), clipped = generate(s, Method::trs, Overlap::clipping);
    for (std::size_t t = 0; t < closed.expected_counts.size(); ++t) {
      EXPECT_NEAR(clipped.expected_counts[t], closed.expected_counts[t], 1e-9 * (1.0 + closed.expected_counts[t]))
          << s.name << ", triangle " << t;
      EXPECT_EQ(clipped.max_density[t], closed.max_density[t]) << s.name << ", triangle " << t;
    }
    EXPECT_EQ(clipped.samples.size(), closed.samples.size()) << s.name;
  }
}

// Eq. 6's approximate overlaps (Overlap::sdf) give triangles the wrong counts: over all cells,
// the samples of TRS counted that way do not follow the density, where counted exactly they do.
TEST(Distribution, RejectsTrsCountedWithTheSdfOverlap) {
  const Scenario s = trs_test::scenarios()[0];
  const auto exact = trs_test::test_all_cells(s, generate(s, Method::trs).samples.span());
  EXPECT_TRUE(exact.passes(kAlpha)) << exact.describe();
  const auto approximate = trs_test::test_all_cells(s, generate(s, Method::trs, Overlap::sdf).samples.span());
  EXPECT_FALSE(approximate.passes(kAlpha)) << approximate.describe();
}

TEST(Distribution, RejectsNaiveStratificationWithWrongPieceWeights) {
  // The pieces drawn in proportion to the square root of their density: the same support, the
  // wrong shares.
  const Scenario s = trs_test::scenarios()[2];
  Frame frame = generate(s, Method::naive);
  core::DensityMap flatter{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  for (float& texel : flatter.texels) texel = std::sqrt(texel);
  cpu::naive_realize(trs_test::texel_triangles(s), {&flatter, 1}, frame.cdf.span(),
                     frame.inverse_permutation.span(), stream_key(s.seed, Stream::naive), 1u << 20,
                     frame.samples);
  EXPECT_FALSE(trs_test::test_per_triangle(s, frame.samples.span()).passes(kAlpha));
}

TEST(Distribution, RejectsTrsWhoseExactDrawsHaveWrongPieceWeights) {
  // Exact draws after one rejection, from the square root of the map: the same support, the
  // wrong shares.
  const Scenario s = trs_test::scenarios()[2];
  Frame frame = generate(s, Method::trs);
  core::DensityMap flatter{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  for (float& texel : flatter.texels) texel = std::sqrt(texel);
  const cpu::RealizationResult r = cpu::realize(
      trs_test::texel_triangles(s), {&flatter, 1}, frame.max_density.span(), frame.cdf.span(),
      frame.inverse_permutation.span(), {stream_key(s.seed, Stream::realization), stream_key(s.seed, Stream::exact)},
      {1u << 20, 1}, frame.samples);
  EXPECT_GT(r.exact, frame.sample_count / 4);
  EXPECT_FALSE(trs_test::test_per_triangle(s, frame.samples.span()).passes(kAlpha));
}

TEST(Distribution, FastRejectionSamplingMatchesTheDensity) {
  for (const Scenario& s : trs_test::scenarios()) {
    const Frame frame = generate(s, Method::frs);
    EXPECT_EQ(frame.exhausted, 0u) << s.name;
    EXPECT_GT(frame.setup_bytes, 0u) << s.name;
    const auto result = trs_test::test_all_cells(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name;
    EXPECT_TRUE(result.passes(kAlpha)) << s.name << "\n" << result.describe();
  }
}

TEST(Distribution, RejectsFastRejectionSamplingWithHalvedBounds) {
  // Every micro-triangle's bound halved: its brighter texels are accepted as often as dimmer ones.
  const Scenario s = trs_test::scenarios()[2];
  Frame frame = generate(s, Method::frs);
  const core::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  const auto records = core::make_triangle_records(s.mesh.view(), 1);
  const auto tris = trs_test::texel_triangles(s);
  core::FrsTable table = core::frs_build(records, tris, {&map, 1});
  for (float& b : table.bound) b *= 0.5f;
  cpu::frs_sample(table, tris, {&map, 1}, frame.sample_count, stream_key(s.seed, Stream::frs), 1u << 20,
                  frame.samples);
  EXPECT_FALSE(trs_test::test_all_cells(s, frame.samples.span()).passes(kAlpha));
}

TEST(Distribution, RejectsTrsThatIgnoresTheMaxDensity) {
  // With a zero bound every candidate on a non-zero texel is accepted: uniform, not D-shaped.
  const Scenario s = trs_test::scenarios()[0];
  Frame frame = generate(s, Method::trs);
  const auto tris = trs_test::texel_triangles(s);
  const core::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  const std::vector<float> no_bound(frame.max_density.size(), 0.0f);
  cpu::realize(tris, {&map, 1}, no_bound, frame.cdf.span(), frame.inverse_permutation.span(),
               {stream_key(s.seed, Stream::realization), stream_key(s.seed, Stream::exact)}, {1u << 20, 0},
               frame.samples);
  EXPECT_FALSE(trs_test::test_per_triangle(s, frame.samples.span()).passes(kAlpha));
}

TEST(Distribution, RejectsTrsWithANonUniformTriangleMap) {
  const Scenario s = trs_test::scenarios()[2];
  Frame frame = generate(s, Method::trs);
  realize_with_wrong_map(s, frame, frame.samples);
  EXPECT_FALSE(trs_test::test_per_triangle(s, frame.samples.span()).passes(kAlpha));
}

TEST(Distribution, RejectsRejectionSamplingWithTooLowABound) {
  // Half the true max: the brightest texels are accepted as often as dimmer ones.
  const Scenario s = trs_test::scenarios()[0];
  Frame frame = generate(s, Method::rejection);
  const core::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  Buffer<double> area_cdf;
  std::vector<std::uint32_t> area_guide;
  const auto records = core::make_triangle_records(s.mesh.view(), 1);
  const float bound = cpu::rejection_distribution(records, {&map, 1}, area_cdf, area_guide);
  cpu::rejection_sample(texel_triangles(s), {&map, 1}, area_cdf.span(), area_guide, 0.5f * bound, frame.sample_count,
                        stream_key(s.seed, Stream::rejection), 1u << 20, frame.samples);
  EXPECT_FALSE(trs_test::test_all_cells(s, frame.samples.span()).passes(kAlpha));
}
