#pragma once
// Per-triangle data the CPU passes read: copied from the caller's mesh once, and the
// texel-space form built each frame (it depends on the maps' sizes).

#include <array>
#include <cstdint>
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

}  // namespace lightsampler::core
