// The unordered cumulative sum (Algorithm 3) against the ordered one: same distribution, any
// order; the inverse permutation maps processing order back to triangles.

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "core/frame_policy.h"
#include "cpu/passes.h"
#include "lightsampler/sampler.h"
#include "sampler_fixtures.h"

using namespace lightsampler;

namespace {

std::vector<std::uint64_t> random_counts(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> kind(0, 3);
  std::vector<std::uint64_t> counts(n);
  for (auto& c : counts) c = kind(rng) == 0 ? 0 : rng() % 1000;  // a quarter are empty
  return counts;
}

/// The CDF holds every element exactly once: sigma^-1 is a permutation and the CDF steps are
/// the counts of the elements it names.
void expect_valid_scan(const std::vector<std::uint64_t>& counts, const Buffer<std::uint64_t>& cdf,
                       const Buffer<std::uint32_t>& inverse) {
  ASSERT_EQ(cdf.size(), counts.size());
  ASSERT_EQ(inverse.size(), counts.size());
  std::vector<char> seen(counts.size(), 0);
  std::uint64_t previous = 0;
  for (std::size_t p = 0; p < counts.size(); ++p) {
    const std::uint32_t element = inverse[p];
    ASSERT_LT(element, counts.size()) << "processing index " << p;
    ASSERT_FALSE(seen[element]) << "element " << element << " appears twice";
    seen[element] = 1;
    ASSERT_EQ(cdf[p] - previous, counts[element]) << "processing index " << p;
    previous = cdf[p];
  }
  EXPECT_EQ(previous, std::accumulate(counts.begin(), counts.end(), std::uint64_t(0)));
}

}  // namespace

TEST(Scan, UnorderedIsAPermutationOfTheOrderedScan) {
  tbb::task_arena arena(2);
  // Sizes around the block size and not multiples of it; block 1 is Algorithm 3 verbatim.
  for (std::size_t n : {1u, 2u, 7u, 255u, 256u, 257u, 1000u, 100003u}) {
    for (std::size_t block : {1u, 16u, 256u}) {
      SCOPED_TRACE("n = " + std::to_string(n) + ", block = " + std::to_string(block));
      const auto counts = random_counts(n, n * 31 + block);
      const std::uint64_t total = std::accumulate(counts.begin(), counts.end(), std::uint64_t(0));
      ASSERT_TRUE(core::unordered_scan_fits(n, total));
      Buffer<std::uint64_t> cdf;
      Buffer<std::uint32_t> inverse;
      arena.execute([&] { cpu::unordered_scan(counts, block, cdf, inverse); });
      expect_valid_scan(counts, cdf, inverse);
    }
  }
}

TEST(Scan, OrderedIsTheInclusivePrefixSum) {
  for (std::size_t n : {0u, 1u, 5u, 70001u}) {
    const auto counts = random_counts(n, n);
    std::vector<std::uint64_t> expected(n);
    std::inclusive_scan(counts.begin(), counts.end(), expected.begin());
    Buffer<std::uint64_t> cdf;
    Buffer<std::uint32_t> inverse;
    cpu::ordered_scan(counts, cdf, inverse);
    ASSERT_EQ(cdf.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(cdf[i], expected[i]);
      ASSERT_EQ(inverse[i], i);
    }
  }
}

TEST(Scan, EmptyInput) {
  Buffer<std::uint64_t> cdf;
  Buffer<std::uint32_t> inverse;
  cpu::unordered_scan({}, 256, cdf, inverse);
  EXPECT_TRUE(cdf.empty());
  EXPECT_TRUE(inverse.empty());
}

TEST(Scan, PackingLimits) {
  // n elements need bit_width(n) bits for the processing index; the sum gets the rest.
  EXPECT_TRUE(core::unordered_scan_fits(0, ~std::uint64_t(0)));  // no elements: every bit is the sum's
  EXPECT_TRUE(core::unordered_scan_fits(1, (std::uint64_t(1) << 63) - 1));
  EXPECT_FALSE(core::unordered_scan_fits(1, std::uint64_t(1) << 63));
  EXPECT_TRUE(core::unordered_scan_fits(0xffffffffull, 0xffffffffull));  // the paper's 32/32 split
  EXPECT_FALSE(core::unordered_scan_fits(0xffffffffull, 0x100000000ull));
  EXPECT_TRUE(core::unordered_scan_fits(0x100000000ull, 0x7fffffffull));
  EXPECT_FALSE(core::unordered_scan_fits(0x100000000ull, 0x80000000ull));
}

TEST(Scan, BeyondTwoToThe32SamplesTheCountsStayExact) {
  // 5e9 samples (more than 2^32) on two triangles: counted and scanned, not realized.
  const trs_test::Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const trs_test::Map map{{1.0f, 3.0f, 2.0f, 4.0f}, 2, 2};
  const DensityMapView view = map.view();
  auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
  Frame frame;
  FrameRequest request;
  request.target_count = 5e9;
  request.scan = ScanOrder::unordered;
  request.realize = false;
  sampler->generate(request, frame);
  EXPECT_EQ(frame.scan_used, ScanOrder::unordered);
  EXPECT_EQ(frame.cdf[frame.cdf.size() - 1], frame.sample_count);
  EXPECT_NEAR(double(frame.sample_count), 5e9, 2.0);
  EXPECT_TRUE(frame.samples.empty());
}

TEST(Scan, AnUnorderedScanThatWouldOverflowIsAnError) {
  // Two triangles need 2 index bits, leaving 62 for the sum: 2^63 samples do not fit.
  const trs_test::Mesh mesh = trs_test::quad(1, 1, 0, 0, 1, 1);
  const trs_test::Map map{{1.0f}, 1, 1};
  const DensityMapView view = map.view();
  auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
  Frame frame;
  FrameRequest request;
  request.target_count = 0x1p63;
  request.realize = false;
  sampler->generate(request, frame);
  EXPECT_EQ(frame.scan_used, ScanOrder::ordered);  // the CPU's automatic choice
  EXPECT_EQ(frame.cdf[1], frame.sample_count);
  EXPECT_EQ(frame.cdf[0] + frame.counts[1], frame.cdf[1]);

  request.scan = ScanOrder::unordered;  // asked for explicitly: an error, never a silent overflow
  EXPECT_THROW(sampler->generate(request, frame), std::overflow_error);
}
