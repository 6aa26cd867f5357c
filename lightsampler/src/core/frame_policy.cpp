#include "core/frame_policy.h"

#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/validate.h"

namespace lightsampler::core {

void begin_frame(const FrameRequest& request, Frame& frame) {
  validate_request(request);
  frame.passes.clear();
  frame.method = request.method;
  frame.candidates = frame.exhausted = frame.exact_draws = 0;
  frame.setup_bytes = 0;
  frame.expected_total = std::numeric_limits<double>::quiet_NaN();
  frame.counting_used.reset();
}

bool unordered_scan_fits(std::uint64_t elements, std::uint64_t total) {
  // The high bits count processed elements (up to `elements`), the low bits hold the partial sum.
  const int index_bits = std::bit_width(elements);
  if (index_bits >= 64) return false;
  return index_bits == 0 || total < (std::uint64_t(1) << (64 - index_bits));
}

ScanOrder choose_scan(ScanOrder requested, ScanOrder preferred, std::uint64_t elements, std::uint64_t total) {
  const bool fits = unordered_scan_fits(elements, total);
  if (requested == ScanOrder::unordered && !fits)
    throw std::overflow_error(std::to_string(elements) + " triangles and " + std::to_string(total) +
                              " samples do not fit one 64-bit packed counter; use the ordered scan");
  if (requested == ScanOrder::lookback && total >= (std::uint64_t(1) << 62))
    throw std::overflow_error(std::to_string(total) +
                              " samples do not fit the lookback scan's 62-bit sums; use the ordered scan");
  if (requested != ScanOrder::automatic) return requested;
  return preferred == ScanOrder::unordered && fits ? ScanOrder::unordered : ScanOrder::ordered;
}

std::uint64_t rejection_sample_count(double target, float max_density, double total_area, std::uint64_t seed) {
  if (!(max_density > 0) || !(total_area > 0)) return 0;
  const PhiloxCounter u = philox4x32({0xffffffffu, 0, 0, 0}, stream_key(seed, Stream::rounding));
  const double whole = std::floor(target);
  return std::uint64_t(whole) + (uniform53(u) < target - whole ? 1 : 0);
}

}  // namespace lightsampler::core
