#pragma once
// Density maps as the CPU backend stores them, and the one texel lookup that the counting pass,
// the realization pass and Sampler::density all use.

#include <cmath>
#include <cstdint>
#include <vector>

#include "lightsampler/mesh.h"

namespace lightsampler::core {

struct DensityMap {
  std::vector<float> texels;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  Addressing addressing = Addressing::wrap;
  float scale = 1.0f;
};

/// Texel index along one axis for lattice cell i (any integer) of a map n texels wide.
inline std::uint32_t address(std::int64_t i, std::uint32_t n, Addressing addressing) {
  if (std::uint64_t(i) < n) return std::uint32_t(i);  // the common case: inside the map
  if (addressing == Addressing::clamp) return i < 0 ? 0u : n - 1;
  if (addressing == Addressing::mirror) {  // period 2n: the map, then the map mirrored
    const std::int64_t period = 2 * std::int64_t(n), r = i % period, m = r < 0 ? r + period : r;
    return std::uint32_t(m < n ? m : period - 1 - m);
  }
  const std::int64_t r = i % std::int64_t(n);
  return std::uint32_t(r < 0 ? r + n : r);
}

/// The stored value of the texel that lattice cell (ix, iy) reads, before the map's scale.
inline float cell_value(const DensityMap& map, std::int64_t ix, std::int64_t iy) {
  return map.texels[std::size_t(address(iy, map.height, map.addressing)) * map.width +
                    address(ix, map.width, map.addressing)];
}

/// Density of lattice cell (ix, iy): texel value times the map's scale.
inline float cell_density(const DensityMap& map, std::int64_t ix, std::int64_t iy) {
  return cell_value(map, ix, iy) * map.scale;
}

/// The texel that lattice cell (ix, iy) reads.
inline Texel cell_texel(const DensityMap& map, std::uint32_t index, std::int64_t ix,
                        std::int64_t iy) {
  return {index, address(ix, map.width, map.addressing), address(iy, map.height, map.addressing)};
}

/// floor(x) as an integer, without the libm call or emulation of baseline x86-64.
inline std::int64_t floor_to_int(float x) {
  const auto i = std::int64_t(x);  // truncates toward zero
  return i - (float(i) > x ? 1 : 0);
}

/// Density at a point given in texel units (u * width, v * height): nearest texel.
inline float point_density(const DensityMap& map, float x, float y) {
  return cell_density(map, floor_to_int(x), floor_to_int(y));
}

}  // namespace lightsampler::core
