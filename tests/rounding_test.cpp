// Stochastic rounding (Algorithm 2, line 14): each N_T is floor(x) or floor(x) + 1 and its
// expectation is x = scale * N-bar_T, so the target count is honoured in expectation.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "cpu/passes.h"
#include "lightsampler/sampler.h"
#include "sampler_fixtures.h"

using namespace lightsampler;

namespace {

/// Deliberately wrong: rounds to nearest, so a fraction below 1/2 never yields a sample.
std::uint64_t round_to_nearest(std::span<const double> expected, Buffer<std::uint64_t>& counts) {
  counts.resize(expected.size());
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) total += counts[i] = std::uint64_t(std::llround(expected[i]));
  return total;
}

/// Hypothesis: E[N] = sum of x. n triangles of expectation x each give N with mean n x and
/// variance n f (1 - f), f the fraction of x. Accept within 5 standard deviations
/// (false alarm about 6e-7).
bool total_within_five_sigma(std::uint64_t total, std::size_t n, double x) {
  const double f = x - std::floor(x);
  const double sigma = std::sqrt(double(n) * f * (1 - f));
  return std::abs(double(total) - double(n) * x) <= 5 * sigma;
}

}  // namespace

TEST(Rounding, EachCountIsTheFloorOrTheCeiling) {
  std::vector<double> expected = {0.0, 0.25, 1.0, 2.5, 7.999, 1e6 + 0.5, 3e10 + 0.125};
  Buffer<std::uint64_t> counts;
  const std::uint64_t total = cpu::round_counts(expected, 1.0, stream_key(1, Stream::rounding), counts);
  std::uint64_t sum = 0;
  for (std::size_t t = 0; t < expected.size(); ++t) {
    const double lo = std::floor(expected[t]);
    EXPECT_TRUE(double(counts[t]) == lo || double(counts[t]) == lo + 1) << "triangle " << t;
    sum += counts[t];
  }
  EXPECT_EQ(total, sum);
  EXPECT_EQ(counts[0], 0u);  // zero expectation: never a sample
  EXPECT_EQ(counts[2], 1u);  // an integer is kept exactly
}

TEST(Rounding, ExpectationIsTheScaledCount) {
  // Seed 3; 200000 triangles of expectation 0.3 (after scaling 0.1 by 3).
  const std::size_t n = 200000;
  const std::vector<double> expected(n, 0.1);
  Buffer<std::uint64_t> counts;
  const std::uint64_t total = cpu::round_counts(expected, 3.0, stream_key(3, Stream::rounding), counts);
  EXPECT_TRUE(total_within_five_sigma(total, n, 0.3)) << "total " << total;
}

TEST(Rounding, TheExpectationCheckRejectsRoundToNearest) {
  const std::size_t n = 200000;
  const std::vector<double> expected(n, 0.3);
  Buffer<std::uint64_t> counts;
  EXPECT_FALSE(total_within_five_sigma(round_to_nearest(expected, counts), n, 0.3));
}

TEST(Rounding, TargetIsHonouredInExpectation) {
  // Hypothesis: over frames with seeds 0..1999, the mean of N equals N_target = 1000.5. N is a
  // sum of independent Bernoulli fractions, so its variance is at most T / 4 per frame.
  const trs_test::Mesh mesh = trs_test::random_triangles(40, 0.0f, 1.0f, 5);
  const trs_test::Map map = trs_test::random_map(8, 8, 0.3, 6);
  const DensityMapView view = map.view();
  auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
  Frame frame;
  FrameRequest request;
  request.target_count = 1000.5;
  request.realize = false;
  const int frames = 2000;
  double sum = 0;
  for (int seed = 0; seed < frames; ++seed) {
    request.seed = std::uint64_t(seed);
    sampler->generate(request, frame);
    ASSERT_EQ(frame.cdf[frame.cdf.size() - 1], frame.sample_count);
    sum += double(frame.sample_count);
  }
  const double sigma_of_mean = std::sqrt(40.0 / 4 / frames);
  EXPECT_NEAR(sum / frames, 1000.5, 5 * sigma_of_mean);
}

TEST(Rounding, SameSeedSameCountsDifferentSeedDifferentCounts) {
  const std::vector<double> expected(1000, 0.5);
  Buffer<std::uint64_t> a, b, c;
  cpu::round_counts(expected, 1.0, stream_key(9, Stream::rounding), a);
  cpu::round_counts(expected, 1.0, stream_key(9, Stream::rounding), b);
  cpu::round_counts(expected, 1.0, stream_key(10, Stream::rounding), c);
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
  EXPECT_FALSE(std::equal(a.begin(), a.end(), c.begin()));
}
