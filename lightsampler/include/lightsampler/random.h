#pragma once
// Counter-based random numbers: Philox4x32-10 (Salmon et al., "Parallel random numbers: as easy
// as 1, 2, 3", SC 2011). A sample's random numbers are a pure function of (key, counter), so the
// output does not depend on thread count, scheduling or backend. The GLSL twin is philox4x32 in
// shaders/common.glsl.

#include <array>
#include <cstdint>

namespace lightsampler {

using PhiloxKey = std::array<std::uint32_t, 2>;
using PhiloxCounter = std::array<std::uint32_t, 4>;

inline PhiloxCounter philox4x32(PhiloxCounter c, PhiloxKey k) {
  constexpr std::uint32_t kM0 = 0xD2511F53u, kM1 = 0xCD9E8D57u;
  constexpr std::uint32_t kW0 = 0x9E3779B9u, kW1 = 0xBB67AE85u;
  for (int round = 0; round < 10; ++round) {
    const std::uint64_t p0 = std::uint64_t(kM0) * c[0];
    const std::uint64_t p1 = std::uint64_t(kM1) * c[2];
    c = {std::uint32_t(p1 >> 32) ^ c[1] ^ k[0], std::uint32_t(p1),
         std::uint32_t(p0 >> 32) ^ c[3] ^ k[1], std::uint32_t(p0)};
    k[0] += kW0;
    k[1] += kW1;
  }
  return c;
}

/// Independent streams drawn from one user seed.
enum class Stream : std::uint32_t {
  realization = 1,  ///< TRS candidates: candidate j of segment s of triangle T
  rounding = 2,     ///< stochastic rounding, counter (triangle, 0, 0, 0)
  rejection = 3,    ///< plain rejection sampling: candidate j of segment s of the output
  naive = 4,        ///< naive stratification: attempt a of slot k of triangle T
  frs = 5,          ///< fast rejection sampling: candidate j of segment s of the output
  exact = 6,        ///< TRS's exact draws: attempt a of slot k of triangle T
};

/// SplitMix64 finaliser: spreads a seed over all 64 bits.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

inline PhiloxKey stream_key(std::uint64_t seed, Stream stream) {
  // Hash the seed first: seeds that differ by a constant must not alias another stream's key.
  const std::uint64_t k = mix64(mix64(seed) + 0x9E3779B97F4A7C15ull * std::uint64_t(stream));
  return {std::uint32_t(k), std::uint32_t(k >> 32)};
}

/// Uniform float in [0, 1) from the top 24 bits: every value is exactly representable.
inline float uniform_float(std::uint32_t bits) { return float(bits >> 8) * 0x1p-24f; }

/// Uniform double in [0, 1) from 32 bits.
inline double uniform_double(std::uint32_t bits) { return double(bits) * 0x1p-32; }

}  // namespace lightsampler
