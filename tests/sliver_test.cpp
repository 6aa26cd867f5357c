// A sliver of density: one triangle whose only lit texel it overlaps by a tiny fraction of its
// area, the sparsity limit the paper itself names. Rejection against D_T^max alone needs about
// 1 / fraction candidates a sample; TRS's exact draws after FrameRequest::exact_after rejections
// in a row bound that, without bias.
//
// Hypothesis H0 (SamplesAreUniformOverTheSliver): the samples are uniform over the sliver, the
// only part of the triangle where the density is positive. Seed 7, 20,000 samples a fraction;
// chi-square over 10 cells of the sliver (a 4 x 4 grid of its legs, clipped to it) at
// trs_test::kDistributionAlpha; a sample outside the sliver fails outright. Shown to reject a
// sampler that draws the sliver with a non-uniform triangle map.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "distribution_check.h"
#include "lightsampler/sampler.h"
#include "lightsampler/random.h"
#include "support/chi_square.h"

using namespace lightsampler;

namespace {

constexpr std::uint32_t kSize = 8;     // the map: kSize x kSize texels, texel (2, 2) lit alone
constexpr double kSamples = 20000;
constexpr std::uint64_t kSeed = 7;

/// The triangle of texel-space corners (0, 0), (4 + d, 0), (0, 4 + d): it overlaps texel
/// [2, 3]^2 in the corner of legs d, a fraction d^2 / (4 + d)^2 of its area.
struct Sliver {
  double fraction, legs;
  std::vector<float> positions{0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::vector<float> uvs;
  std::vector<std::uint32_t> indices{0, 1, 2};
  std::vector<float> texels = std::vector<float>(kSize * kSize, 0.0f);

  explicit Sliver(double f) : fraction(f), legs(4.0 * std::sqrt(f) / (1.0 - std::sqrt(f))) {
    const float corner = float((4.0 + legs) / kSize);
    uvs = {0, 0, corner, 0, 0, corner};
    texels[2 * kSize + 2] = 1.0f;
  }

  /// The sliver's own coordinates (s, t) of a sample: (0, 0) at the texel's corner, the sliver
  /// is s, t >= 0, s + t <= 1.
  std::array<double, 2> local(const Sample& x) const {
    const double side = (4.0 + legs);
    return {(double(x.b1) * side - 2.0) / legs, (double(x.b2) * side - 2.0) / legs};
  }

  Frame generate(std::uint32_t exact_after, std::uint32_t max_tries = FrameRequest{}.max_tries) const {
    const DensityMapView map{texels, kSize, kSize};
    Frame frame;
    make_cpu_sampler({positions, uvs, indices, {}}, {&map, 1})
        ->generate({.seed = kSeed, .target_count = kSamples, .max_tries = max_tries, .exact_after = exact_after}, frame);
    return frame;
  }
};

/// Chi-square of the samples' local coordinates over a 4 x 4 grid of the legs' square clipped
/// to the sliver: 6 whole cells (1/8 of the sliver each) and 4 halved along the hypotenuse
/// (1/16 each). A point outside the sliver (beyond float rounding) lands in an impossible cell.
trs_test::ChiSquareResult test_uniform(const Sliver& sliver, std::span<const Sample> samples) {
  std::vector<double> observed(17, 0.0), expected(17, 0.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (i + j <= 3) expected[4 * i + j] = (i + j < 3 ? 1.0 / 8 : 1.0 / 16) * double(samples.size());
  const double slack = 1e-3;  // float barycentrics of a sliver a few 1e-3 texels wide
  for (const Sample& x : samples) {
    const auto [s, t] = sliver.local(x);
    if (s < -slack || t < -slack || s + t > 1 + slack) {
      observed[16] += 1;
      continue;
    }
    const int i = std::clamp(int(s * 4), 0, 3), j = std::clamp(int(t * 4), 0, 3);
    observed[i + j <= 3 ? 4 * i + j : 16] += 1;  // past the diagonal only by rounding
  }
  return trs_test::chi_square_test(observed, expected);
}

}  // namespace

TEST(Sliver, SamplesAreUniformOverTheSliver) {
  for (double fraction : {1e-2, 1e-4, 1e-6}) {
    SCOPED_TRACE(fraction);
    const Sliver sliver(fraction);
    const Frame frame = sliver.generate(FrameRequest{}.exact_after);
    EXPECT_EQ(frame.exhausted, 0u);
    if (fraction < 1e-3) EXPECT_GT(frame.exact_draws, frame.sample_count / 2) << "exact draws fill most slots";
    const auto result = test_uniform(sliver, frame.samples.span());
    EXPECT_TRUE(result.passes(trs_test::kDistributionAlpha)) << result.describe();
  }
}

TEST(Sliver, TriesStayBoundedDownToOneMillionth) {
  // Each segment of up to 256 slots tries at most exact_after candidates in a row before its
  // exact draws, which take one attempt each unless rounding leaves a point outside its texel.
  for (double fraction : {1e-4, 1e-6, 1e-8}) {
    SCOPED_TRACE(fraction);
    const Frame frame = Sliver(fraction).generate(FrameRequest{}.exact_after);
    const double segments = std::ceil(double(frame.sample_count) / 256);
    EXPECT_LT(double(frame.candidates), segments * (FrameRequest{}.exact_after + 16) + 2.0 * double(frame.sample_count));
    EXPECT_EQ(frame.exhausted, 0u);
  }
}

TEST(Sliver, RejectionAloneRunsOutOfTries) {
  // The paper's rule (exact_after 0): at one millionth, 2^12 tries a slot are far too few, and
  // the slots that give up hold rejected candidates, outside the sliver.
  const Sliver sliver(1e-6);
  const Frame frame = sliver.generate(0, 1u << 12);
  EXPECT_GT(frame.exhausted, frame.sample_count / 2);
  EXPECT_EQ(frame.exact_draws, 0u);
  EXPECT_FALSE(test_uniform(sliver, frame.samples.span()).passes(trs_test::kDistributionAlpha));
}

TEST(Sliver, RejectsANonUniformTriangleMapOverTheSliver) {
  // Points of the sliver with b2 = u1 (1 - u0) for its local corner: inside it, crowding one
  // vertex.
  const Sliver sliver(1e-6);
  const double side = 4.0 + sliver.legs;
  std::vector<Sample> wrong;
  for (std::uint32_t k = 0; k < std::uint32_t(kSamples); ++k) {
    const PhiloxCounter u = philox4x32({k, 0, 0, 0}, stream_key(kSeed, Stream::exact));
    const double s = uniform_float(u[0]), t = uniform_float(u[1]) * (1.0 - s);
    wrong.push_back({0, float((2.0 + s * sliver.legs) / side), float((2.0 + t * sliver.legs) / side)});
  }
  EXPECT_FALSE(test_uniform(sliver, wrong).passes(trs_test::kDistributionAlpha));
}
