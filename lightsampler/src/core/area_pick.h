#pragma once
// Plain rejection sampling's pick of a triangle by area: the first triangle whose inclusive area
// CDF exceeds u times the total area. A guide table (Chen and Asau's cutpoints) narrows the
// binary search to about one bucket of the CDF, so a pick costs a few loads whatever the
// triangle count. The GLSL twin is pick_by_cdf in shaders/cdf_pick.glsl; both give exactly
// the triangle a binary search over the whole CDF gives.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace lightsampler::core {

/// K + 1 cutpoints for a CDF of K > 0 entries: guide[k] is the first index whose CDF exceeds
/// k / K of the total (k < K), and guide[K] the last index.
inline std::vector<std::uint32_t> area_guide(std::span<const double> cdf) {
  const std::size_t k_count = cdf.size();
  std::vector<std::uint32_t> guide(k_count + 1);
  const double total = cdf.empty() ? 0.0 : cdf.back();
  std::size_t i = 0;
  for (std::size_t k = 0; k < k_count; ++k) {
    const double boundary = total * double(k) / double(k_count);
    while (i + 1 < k_count && !(cdf[i] > boundary)) ++i;
    guide[k] = std::uint32_t(i);
  }
  if (k_count > 0) guide[k_count] = std::uint32_t(k_count - 1);
  return guide;
}

/// The triangle for u in [0, 1): the first index whose CDF exceeds u * total, or the last. The
/// bucket of u is widened by one on each side, so that rounding in u * K cannot miss it.
inline std::uint32_t pick_by_area(std::span<const double> cdf, std::span<const std::uint32_t> guide, double u) {
  const auto k_count = std::uint32_t(cdf.size());
  const std::uint32_t k = std::min(std::uint32_t(u * double(k_count)), k_count - 1);
  std::uint32_t lo = guide[k > 0 ? k - 1 : 0], hi = guide[std::min(k + 2, k_count)];
  const double target = u * cdf.back();
  while (lo < hi) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    if (cdf[mid] > target) hi = mid; else lo = mid + 1;
  }
  return lo;
}

}  // namespace lightsampler::core
