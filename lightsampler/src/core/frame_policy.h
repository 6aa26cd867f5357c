#pragma once
// What every backend decides the same way each frame: the frame's reset, which scan it runs and
// when that is an error, and how many samples plain rejection sampling draws. One copy, so that
// backends that promise the same samples cannot drift apart.

#include <cstdint>

#include "lightsampler/random.h"
#include "lightsampler/sampler.h"

namespace lightsampler::core {

/// Validates the request, then clears what a backend reports: passes, totals, counting path.
void begin_frame(const FrameRequest& request, Frame& frame);

/// Whether Algorithm 3 can pack (processing index, partial sum) into one 64-bit word.
bool unordered_scan_fits(std::uint64_t elements, std::uint64_t total);

/// The scan of a frame: the one requested, or `preferred` (the backend's faster one) when the
/// request leaves it to the sampler. An unordered scan that cannot pack `elements` and `total`
/// falls back to the ordered one when automatic, and throws std::overflow_error when requested.
/// So does a lookback scan of a total of 2^62 or more (its states pack a 2-bit flag and the sum).
ScanOrder choose_scan(ScanOrder requested, ScanOrder preferred, std::uint64_t elements, std::uint64_t total);

/// Uniform double in [0, 1) with 53 random bits: P(u < f) = f for any double fraction f.
inline double uniform53(const PhiloxCounter& r) {
  return double(((std::uint64_t(r[0]) << 32) | r[1]) >> 11) * 0x1p-53;
}

/// Samples of plain rejection sampling: none when nothing can be drawn (no positive density or
/// no area), else the target rounded stochastically (one draw of the rounding stream), so that
/// E[N] = target as with TRS.
std::uint64_t rejection_sample_count(double target, float max_density, double total_area, std::uint64_t seed);

}  // namespace lightsampler::core
