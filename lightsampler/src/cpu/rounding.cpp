#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "cpu/passes.h"

namespace lightsampler::cpu {

namespace {

/// Uniform double in [0, 1) with 53 random bits: P(u < f) = f for any double fraction f.
double uniform53(const PhiloxCounter& r) {
  return double(((std::uint64_t(r[0]) << 32) | r[1]) >> 11) * 0x1p-53;
}

}  // namespace

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
          const double u = uniform53(philox4x32({std::uint32_t(t), 0, 0, 0}, key));
          counts[t] = std::uint64_t(whole) + (u < x - whole ? 1 : 0);
          total += counts[t];
        }
        return total;
      },
      std::plus<>());
}

std::uint64_t round_total(double target, std::uint64_t seed) {
  const PhiloxCounter u = philox4x32({0xffffffffu, 0, 0, 0}, stream_key(seed, Stream::rounding));
  const double whole = std::floor(target);
  return std::uint64_t(whole) + (uniform53(u) < target - whole ? 1 : 0);
}

}  // namespace lightsampler::cpu
