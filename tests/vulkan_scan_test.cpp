// The device's ordered scans: the single-pass lookback scan against the multi-pass ordered one,
// bit for bit, also when every tile takes the decoupled fallback instead of waiting.

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "vulkan/passes.h"
#include "vulkan_fixture.h"

using namespace lightsampler;
using trs_test::VulkanTest;

namespace {

/// Values below `limit`, a fraction of them zero.
std::vector<std::uint64_t> random_counts(std::size_t n, std::uint64_t limit, double zeros, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::uint64_t> value(0, limit - 1);
  std::bernoulli_distribution zero(zeros);
  std::vector<std::uint64_t> counts(n);
  for (std::uint64_t& c : counts) c = zero(rng) ? 0 : value(rng);
  return counts;
}

class DeviceScan : public VulkanTest {
 protected:
  /// The inclusive scans of `counts` by the ordered and the lookback scan (with `polls`).
  std::pair<std::vector<std::uint64_t>, std::vector<std::uint64_t>> scans(const std::vector<std::uint64_t>& counts,
                                                                          std::uint32_t polls) {
    const vk::Pipelines pipelines(*context);
    vk::OrderedScan ordered(*context);
    vk::LookbackScan lookback(*context);
    const VkDeviceSize bytes = std::max<std::size_t>(counts.size(), 1) * sizeof(std::uint64_t);
    const vk::Buffer source = context->create_buffer(bytes), by_ordered = context->create_buffer(bytes),
                     by_lookback = context->create_buffer(bytes);
    context->upload(source, 0, counts.data(), counts.size() * sizeof(std::uint64_t));
    vk::Commands c = context->begin();
    ordered.record(c, pipelines, source.address(), by_ordered.address(), counts.size());
    lookback.record(c, source.address(), by_lookback.address(), counts.size(), polls);
    context->submit(c);
    std::vector<std::uint64_t> a(counts.size()), b(counts.size());
    context->download(by_ordered, 0, a.data(), a.size() * sizeof(std::uint64_t));
    context->download(by_lookback, 0, b.data(), b.size() * sizeof(std::uint64_t));
    return {a, b};
  }

  /// Both scans equal the host's prefix sum.
  void expect_prefix_sums(const std::vector<std::uint64_t>& counts, std::uint32_t polls) {
    const auto [ordered, lookback] = scans(counts, polls);
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
      sum += counts[i];
      ASSERT_EQ(ordered[i], sum) << "element " << i;
      ASSERT_EQ(lookback[i], sum) << "element " << i;
    }
  }
};

TEST_F(DeviceScan, LookbackEqualsOrderedOnTileBoundaries) {
  if (!context->capabilities().vulkan_memory_model) GTEST_SKIP() << "no vulkanMemoryModel";
  const std::size_t tile = gpu::kLookbackTile;
  for (std::size_t n : {std::size_t(1), tile - 1, tile, tile + 1, 37 * tile + 5}) {
    SCOPED_TRACE(n);
    expect_prefix_sums(random_counts(n, 1u << 20, 0.3, n), gpu::kLookbackPolls);
  }
}

TEST_F(DeviceScan, LookbackEqualsOrderedOnAMillionElementsNearThe62BitLimit) {
  if (!context->capabilities().vulkan_memory_model) GTEST_SKIP() << "no vulkanMemoryModel";
  const std::size_t n = 1000000;
  expect_prefix_sums(random_counts(n, (std::uint64_t(1) << 62) / n, 0.1, 5), gpu::kLookbackPolls);
}

TEST_F(DeviceScan, LookbackOfZerosIsZero) {
  if (!context->capabilities().vulkan_memory_model) GTEST_SKIP() << "no vulkanMemoryModel";
  expect_prefix_sums(std::vector<std::uint64_t>(5 * gpu::kLookbackTile + 7, 0), gpu::kLookbackPolls);
}

TEST_F(DeviceScan, LookbackFallbackAloneGivesTheSameSums) {
  // With no polls every tile reduces each of its predecessors itself, down to tile 0.
  if (!context->capabilities().vulkan_memory_model) GTEST_SKIP() << "no vulkanMemoryModel";
  const std::size_t tile = gpu::kLookbackTile;
  for (std::size_t n : {std::size_t(1), tile + 1, 19 * tile + 3}) {
    SCOPED_TRACE(n);
    expect_prefix_sums(random_counts(n, std::uint64_t(1) << 40, 0.2, n + 1), 0);
  }
}

TEST_F(DeviceScan, LookbackWithoutTheMemoryModelIsRefused) {
  if (context->capabilities().vulkan_memory_model) GTEST_SKIP() << "the device has vulkanMemoryModel";
  vk::LookbackScan lookback(*context);
  vk::Commands c = context->begin();
  EXPECT_THROW(lookback.record(c, 0, 0, 1), std::invalid_argument);
}

}  // namespace
