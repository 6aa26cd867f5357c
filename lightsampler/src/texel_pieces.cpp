#include "lightsampler/texel_pieces.h"

#include "core/piece_draw.h"

namespace lightsampler {

Barycentrics uniform_point(const TexelPiece& piece, float u_fan, float u0, float u1) {
  core::BaryPolygon polygon;
  polygon.n = int(piece.vertex_count);
  for (std::uint32_t i = 0; i < piece.vertex_count; ++i) polygon.v[i] = piece.vertices[i];
  const auto [b1, b2] = core::point_in(polygon, 0.5 * piece.area, u_fan, u0, u1);
  return {float(b1), float(b2)};
}

}  // namespace lightsampler
