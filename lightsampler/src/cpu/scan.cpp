#include <atomic>
#include <bit>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_scan.h>

#include "cpu/passes.h"

namespace lightsampler::cpu {

void unordered_scan(std::span<const std::uint64_t> counts, std::size_t block, Buffer<std::uint64_t>& cdf,
                    Buffer<std::uint32_t>& inverse_permutation) {
  const std::size_t n = counts.size();
  cdf.resize(n);
  inverse_permutation.resize(n);
  if (n == 0) return;
  const int sum_bits = 64 - std::bit_width(std::uint64_t(n));
  const std::uint64_t sum_mask = (std::uint64_t(1) << sum_bits) - 1;
  std::atomic<std::uint64_t> counter{0};
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, block),
      [&](const tbb::blocked_range<std::size_t>& r) {
        std::uint64_t block_sum = 0;
        for (std::size_t i = r.begin(); i != r.end(); ++i) block_sum += counts[i];
        // One atomic reserves both the output slots and the partial sum for the whole block.
        const std::uint64_t packed =
            counter.fetch_add(block_sum + (std::uint64_t(r.size()) << sum_bits),
                              std::memory_order_relaxed);
        std::uint64_t sum = packed & sum_mask;
        std::uint64_t slot = packed >> sum_bits;
        for (std::size_t i = r.begin(); i != r.end(); ++i, ++slot) {
          sum += counts[i];
          cdf[slot] = sum;
          inverse_permutation[slot] = std::uint32_t(i);
        }
      },
      tbb::simple_partitioner());
}

void ordered_scan(std::span<const std::uint64_t> counts, Buffer<std::uint64_t>& cdf,
                  Buffer<std::uint32_t>& inverse_permutation) {
  const std::size_t n = counts.size();
  cdf.resize(n);
  inverse_permutation.resize(n);
  tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, n, 1 << 14), std::uint64_t(0),
      [&](const tbb::blocked_range<std::size_t>& r, std::uint64_t sum, bool is_final) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          sum += counts[i];
          if (is_final) {
            cdf[i] = sum;
            inverse_permutation[i] = std::uint32_t(i);
          }
        }
        return sum;
      },
      std::plus<>());
}

}  // namespace lightsampler::cpu
