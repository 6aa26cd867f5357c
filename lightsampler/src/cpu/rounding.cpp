#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/frame_policy.h"
#include "cpu/passes.h"

namespace lightsampler::cpu {

std::uint64_t round_counts(std::span<const double> expected_counts, double scale, PhiloxKey key,
                           Buffer<std::uint64_t>& counts) {
  const std::size_t n = expected_counts.size();
  counts.resize(n);
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 4096), std::uint64_t(0),
      [&](const tbb::blocked_range<std::size_t>& r, std::uint64_t total) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
          const double x = scale * expected_counts[t];
          const double whole = std::floor(x);
          const double u = core::uniform53(philox4x32({std::uint32_t(t), 0, 0, 0}, key));
          counts[t] = std::uint64_t(whole) + (u < x - whole ? 1 : 0);
          total += counts[t];
        }
        return total;
      },
      std::plus<>());
}

}  // namespace lightsampler::cpu
