#pragma once
// Non-owning views of the inputs: a triangle mesh with UVs, and density maps mapped onto it.

#include <cstdint>
#include <span>

namespace lightsampler {

/// Per-triangle map index meaning "no density map": the triangle has zero density.
inline constexpr std::uint32_t kNoMap = 0xffffffffu;

/// A triangle mesh as the caller stores it. Nothing is copied or retained: the sampler reads it
/// while it is constructed.
struct MeshView {
  std::span<const float> positions;         ///< 3 floats per vertex, world units
  std::span<const float> uvs;               ///< 2 floats per vertex, see DensityMapView for the convention
  std::span<const std::uint32_t> indices;   ///< 3 vertex indices per triangle
  std::span<const std::uint32_t> triangle_maps;  ///< density map per triangle or kNoMap; empty: all map 0

  std::uint64_t triangle_count() const { return indices.size() / 3; }
  std::uint64_t vertex_count() const { return positions.size() / 3; }
};

/// What a lookup outside [0,1] in UV reads: the map repeated (glTF's REPEAT), its edge texels
/// (CLAMP_TO_EDGE), or the map repeated with every other copy mirrored (MIRRORED_REPEAT).
enum class Addressing : std::uint32_t { wrap = 0, clamp = 1, mirror = 2 };

/// A density map: samples per unit of world area, nearest-texel lookup.
/// Texel (i, j) covers u in [i/width, (i+1)/width) and v in [j/height, (j+1)/height): row 0 is at
/// v = 0 (the glTF convention; loaders of other conventions flip v).
struct DensityMapView {
  std::span<const float> texels;  ///< width * height finite, non-negative values, row-major
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  Addressing addressing = Addressing::wrap;
  float scale = 1.0f;             ///< multiplies every texel (an emitter's strength)
};

/// One texel of one density map: column x, row y (row 0 at v = 0).
struct Texel {
  std::uint32_t map;
  std::uint32_t x;
  std::uint32_t y;
};

}  // namespace lightsampler
