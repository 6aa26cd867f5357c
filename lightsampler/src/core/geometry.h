#pragma once
// Per-triangle data the CPU passes read: copied from the caller's mesh once, and the
// texel-space form built each frame (it depends on the maps' sizes).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "core/density.h"
#include "lightsampler/mesh.h"

namespace lightsampler::core {

/// What the sampler keeps of one triangle: its UVs, world area and map.
struct TriangleRecord {
  float uv[3][2];
  double area;  ///< world units squared
  std::uint32_t map;  ///< kNoMap: zero density
};

/// The map of triangle `t`: its own, else the first (if any).
inline std::uint32_t map_of_triangle(const MeshView& mesh, std::size_t t, std::size_t map_count) {
  if (!mesh.triangle_maps.empty()) return mesh.triangle_maps[t];
  return map_count > 0 ? 0u : kNoMap;
}

/// The record of a triangle with these corners and map (kNoMap: none).
TriangleRecord make_triangle_record(const float (&positions)[3][3], const float (&uvs)[3][2], std::uint32_t map);
std::vector<TriangleRecord> make_triangle_records(const MeshView& mesh, std::size_t map_count);

/// A triangle in its map's texel space, as the realization pass reads it: a point with
/// barycentrics (b1, b2) is at origin + b1 * edge1 + b2 * edge2. A triangle whose UVs are
/// degenerate has zero edges and its origin at the UV centroid: its density is that texel's.
struct TexelTriangle {
  float origin[2];
  float edge1[2];
  float edge2[2];
  std::uint32_t map;
};

/// UV area below which a triangle is treated as UV-degenerate (texel units squared).
inline constexpr double kDegenerateUvArea = 1e-12;

TexelTriangle make_texel_triangle(const TriangleRecord& t, std::span<const DensityMap> maps);

/// A point of the triangle in texel units; every lookup below goes through it.
inline std::array<float, 2> texel_space_point(const TexelTriangle& t, float b1, float b2) {
  return {t.origin[0] + b1 * t.edge1[0] + b2 * t.edge2[0],
          t.origin[1] + b1 * t.edge1[1] + b2 * t.edge2[1]};
}

inline float texel_triangle_density(const TexelTriangle& t, std::span<const DensityMap> maps,
                                    float b1, float b2) {
  if (t.map == kNoMap) return 0.0f;
  const auto [x, y] = texel_space_point(t, b1, b2);
  return point_density(maps[t.map], x, y);
}

inline std::optional<Texel> texel_triangle_texel(const TexelTriangle& t,
                                                 std::span<const DensityMap> maps, float b1,
                                                 float b2) {
  if (t.map == kNoMap) return std::nullopt;
  const auto [x, y] = texel_space_point(t, b1, b2);
  return cell_texel(maps[t.map], t.map, floor_to_int(x), floor_to_int(y));
}

/// How far inside its texel, in texels, a point of `t` must lie to read the same texel however
/// it is computed (a part of the triangle with its own corners rounded to floats, and
/// barycentrics mapped between the two). Each way rounds a handful of times at the magnitude of
/// the triangle's texel coordinates, by 2^-24 of it at most each; the margin is 2^-18 of it, and
/// infinite where that would be half a texel or more: no point is then clear.
inline float texel_edge_margin(const TexelTriangle& t) {
  const float magnitude =
      std::max(std::abs(t.origin[0]) + std::abs(t.edge1[0]) + std::abs(t.edge2[0]),
               std::abs(t.origin[1]) + std::abs(t.edge1[1]) + std::abs(t.edge2[1]));
  return magnitude < 0x1p17f ? magnitude * 0x1p-18f : std::numeric_limits<float>::infinity();
}

/// Whether the point lies `margin` (texel_edge_margin(t)) or more inside its texel.
inline bool clear_of_texel_edges(const TexelTriangle& t, float margin, float b1, float b2) {
  const auto [x, y] = texel_space_point(t, b1, b2);
  // Distance to the nearest lattice line: adding and removing 1.5 * 2^23 rounds to an integer,
  // exactly below 2^22, where every finite margin holds (branch-free, where floor_to_int
  // converts twice).
  const auto clear = [margin](float v) {
    constexpr float kRound = 0x1.8p23f;
    return std::abs(v - ((v + kRound) - kRound)) > margin;
  };
  return clear(x) && clear(y);
}

inline bool clear_of_texel_edges(const TexelTriangle& t, float b1, float b2) {
  return clear_of_texel_edges(t, texel_edge_margin(t), b1, b2);
}

}  // namespace lightsampler::core
