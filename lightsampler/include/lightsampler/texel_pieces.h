#pragma once
// A triangle cut along the texel lattice of its density map: one convex piece per texel cell it
// overlaps, in the triangle's barycentric plane, so that a point drawn in a piece is already a
// sample's barycentrics. Exact texel-proportional draws stand on these (naive stratification,
// TRS's exact draws); Sampler::texel_pieces gives them to callers that draw that way themselves.

#include <array>
#include <cstdint>

#include "lightsampler/mesh.h"
#include "lightsampler/triangle_map.h"

namespace lightsampler {

struct TexelPiece {
  /// The lattice cell the piece lies in, in texels from UV (0, 0): beyond the map when UVs are,
  /// so that wrapping texels are told apart. Sampler::texel_piece_point cuts it again from these.
  std::int64_t cell_x, cell_y;
  Texel texel;    ///< the texel the cell reads, after addressing
  float density;  ///< that texel's density, scaled: what Sampler::density reads in the piece
  double area;    ///< the piece's share of the triangle's area
  std::uint32_t vertex_count;
  std::array<std::array<double, 2>, 7> vertices;  ///< (b1, b2) of a convex polygon
};

/// A uniform point of `piece`, from three uniforms in [0, 1): a triangle of its fan from the
/// first vertex in proportion to area, then a uniform point of that triangle. Rounding can put a
/// point on a cell's edge into the neighbouring texel: check Sampler::texel if that matters.
Barycentrics uniform_point(const TexelPiece& piece, float u_fan, float u0, float u1);

}  // namespace lightsampler
