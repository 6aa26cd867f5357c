// Random numbers and the uniform triangle map: Philox4x32-10 against the published known answers,
// the float conversion's range, stream keys, and a chi-square test that triangle_map is uniform
// (with a deliberately wrong map to show that the test can fail).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "lightsampler/random.h"
#include "lightsampler/triangle_map.h"
#include "support/chi_square.h"

namespace {

using lightsampler::PhiloxCounter;
using lightsampler::PhiloxKey;

TEST(Philox, KnownAnswers) {
  // Random123's kat_vectors, the three "philox4x32 10" lines (counter, key, expected output).
  struct Vector {
    PhiloxCounter counter;
    PhiloxKey key;
    PhiloxCounter expected;
  };
  const Vector vectors[] = {
      {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
      {{0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
       {0xffffffff, 0xffffffff},
       {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
      {{0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
       {0xa4093822, 0x299f31d0},
       {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
  };
  for (const Vector& v : vectors) EXPECT_EQ(lightsampler::philox4x32(v.counter, v.key), v.expected);
}

TEST(UniformFloat, CoversZeroToOneExclusive) {
  // The top 24 bits become k * 2^-24: 0 from all-zero bits, the largest float below 1 from all-one
  // bits, never 1 itself.
  EXPECT_EQ(lightsampler::uniform_float(0), 0.0f);
  EXPECT_EQ(lightsampler::uniform_float(0xffffffffu), 1.0f - 0x1p-24f);
  EXPECT_LT(lightsampler::uniform_float(0xffffffffu), 1.0f);
  EXPECT_EQ(lightsampler::uniform_float(0x000000ffu), 0.0f);  // below the 24 bits used
  EXPECT_EQ(lightsampler::uniform_float(0x00000100u), 0x1p-24f);
  EXPECT_EQ(lightsampler::uniform_float(0x80000000u), 0.5f);
  EXPECT_EQ(lightsampler::uniform_double(0), 0.0);
  EXPECT_LT(lightsampler::uniform_double(0xffffffffu), 1.0);
  // Monotone, in [0, 1), and on the 2^-24 grid, over bit patterns spread across the range.
  float previous = 0;
  for (std::uint64_t bits = 0; bits <= 0xffffffffu; bits += 0x10001) {
    const float u = lightsampler::uniform_float(std::uint32_t(bits));
    ASSERT_GE(u, previous);
    ASSERT_LT(u, 1.0f);
    ASSERT_EQ(u * 0x1p24f, std::floor(u * 0x1p24f));
    previous = u;
  }
}

TEST(StreamKey, DistinctForDistinctSeedsAndStreams) {
  // Seeds as a renderer uses them (frame numbers), and seeds at the top of the 64-bit range.
  std::set<std::uint64_t> keys;
  std::size_t made = 0;
  for (const std::uint64_t base : {std::uint64_t{0}, ~std::uint64_t{0} - 9999}) {
    for (std::uint64_t seed = base; seed < base + 10000 && seed >= base; ++seed) {
      for (const auto stream : {lightsampler::Stream::realization, lightsampler::Stream::rounding,
                                lightsampler::Stream::rejection}) {
        const PhiloxKey k = lightsampler::stream_key(seed, stream);
        keys.insert(std::uint64_t(k[1]) << 32 | k[0]);
        ++made;
      }
    }
  }
  EXPECT_EQ(keys.size(), made);
  // A pure function of its arguments.
  EXPECT_EQ(lightsampler::stream_key(42, lightsampler::Stream::rounding),
            lightsampler::stream_key(42, lightsampler::Stream::rounding));
}

/// The random inputs of the triangle-map tests: Philox words 0 and 1 of counter (i, 0, 0, 0),
/// as the library turns them into floats.
struct UniformPair {
  float u0, u1;
};
UniformPair uniform_pair(std::uint32_t i, PhiloxKey key) {
  const PhiloxCounter out = lightsampler::philox4x32({i, 0, 0, 0}, key);
  return {lightsampler::uniform_float(out[0]), lightsampler::uniform_float(out[1])};
}

bool inside_triangle(lightsampler::Barycentrics b) {
  // Summed in double: exact for triangle_map's outputs (multiples of 2^-25 in [0, 1]).
  return std::isfinite(b.b1) && std::isfinite(b.b2) && b.b1 >= 0 && b.b2 >= 0 && double(b.b1) + double(b.b2) <= 1;
}

TEST(TriangleMap, StaysInsideTheTriangle) {
  // Every pair of extreme inputs: the 256 smallest floats of the 2^-24 grid, the 256 around 1/2,
  // the 256 largest below 1 (the square's edges, corners and diagonal u0 = u1 included).
  std::vector<float> edge;
  for (int k = 0; k < 256; ++k) {
    edge.push_back(float(k) * 0x1p-24f);
    edge.push_back(float((1 << 23) - 128 + k) * 0x1p-24f);
    edge.push_back(float((1 << 24) - 256 + k) * 0x1p-24f);
  }
  for (float u0 : edge) {
    for (float u1 : edge) {
      const lightsampler::Barycentrics b = lightsampler::triangle_map(u0, u1);
      ASSERT_TRUE(inside_triangle(b)) << "u0 " << u0 << " u1 " << u1 << ": b1 " << b.b1 << " b2 " << b.b2;
    }
  }
  // And a million ordinary inputs. Seed 1.
  const PhiloxKey key = lightsampler::stream_key(1, lightsampler::Stream::realization);
  for (std::uint32_t i = 0; i < 1000000; ++i) {
    const UniformPair u = uniform_pair(i, key);
    const lightsampler::Barycentrics b = lightsampler::triangle_map(u.u0, u.u1);
    ASSERT_TRUE(inside_triangle(b)) << "u0 " << u.u0 << " u1 " << u.u1 << ": b1 " << b.b1 << " b2 " << b.b2;
  }
}

/// The triangle b1, b2 >= 0, b1 + b2 <= 1 cut by the lines b1 = i/n, b2 = j/n and b1 + b2 = k/n into
/// n^2 congruent cells of equal area: in square (i, j) of the n x n grid, a lower cell
/// (fraction sum <= 1) and an upper one. Squares on or beyond the diagonal have cells of
/// probability 0, and the last index collects points outside the triangle (probability 0 too):
/// a uniform map never puts a sample in any of those.
class TriangleCells {
 public:
  explicit TriangleCells(int n) : n_(n) {}

  std::size_t count() const { return 2 * std::size_t(n_) * n_ + 1; }

  std::size_t cell(lightsampler::Barycentrics b) const {
    if (!inside_triangle(b)) return count() - 1;
    // Closed triangle: a point on the far edge belongs to the last row or column.
    const double x = double(b.b1) * n_, y = double(b.b2) * n_;
    const int i = std::min(int(x), n_ - 1), j = std::min(int(y), n_ - 1);
    const bool upper = (x - i) + (y - j) > 1;
    return 2 * (std::size_t(i) * n_ + j) + upper;
  }

  std::vector<double> expected(double samples) const {
    std::vector<double> e(count(), 0);
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; i + j < n_; ++j) {
        e[2 * (std::size_t(i) * n_ + j)] = samples / (double(n_) * n_);
        if (i + j < n_ - 1) e[2 * (std::size_t(i) * n_ + j) + 1] = samples / (double(n_) * n_);
      }
    }
    return e;
  }

 private:
  int n_;
};

/// Chi-square test of a square-to-triangle map against the uniform distribution, on 64^2 = 4096
/// equal cells, 2^22 samples (1024 expected per cell), inputs from Philox with seed 2024.
template <class Map>
trs_test::ChiSquareResult uniformity_test(Map map) {
  const TriangleCells cells(64);
  const std::uint32_t samples = 1u << 22;
  const PhiloxKey key = lightsampler::stream_key(2024, lightsampler::Stream::realization);
  std::vector<double> observed(cells.count(), 0);
  for (std::uint32_t i = 0; i < samples; ++i) {
    const UniformPair u = uniform_pair(i, key);
    observed[cells.cell(map(u.u0, u.u1))] += 1;
  }
  return trs_test::chi_square_test(observed, cells.expected(samples));
}

constexpr double kAlpha = 0.01;

TEST(TriangleMap, IsUniform) {
  // Hypothesis: triangle_map of Philox uniforms is uniform on the triangle. Rejected when
  // p < 0.01 or when any sample falls outside the triangle (one test: no Šidák correction).
  const trs_test::ChiSquareResult r = uniformity_test(lightsampler::triangle_map);
  EXPECT_TRUE(r.passes(kAlpha)) << r.describe();
  EXPECT_EQ(r.dof, 4095);
}

TEST(TriangleMap, UniformityTestRejectsAWrongMap) {
  // The same test on a classic mistake, b1 = u0, b2 = u1 (1 - u0): it lands inside the triangle,
  // but with density proportional to 1 / (1 - b1), crowding the b1 = 1 corner. The test must
  // reject it, or it could not have caught a broken triangle_map either.
  auto wrong = [](float u0, float u1) { return lightsampler::Barycentrics{u0, u1 * (1 - u0)}; };
  const trs_test::ChiSquareResult r = uniformity_test(wrong);
  EXPECT_TRUE(r.impossible.empty()) << r.describe();
  EXPECT_LT(r.p_value, kAlpha) << r.describe();
  EXPECT_FALSE(r.passes(kAlpha));
}

}  // namespace
