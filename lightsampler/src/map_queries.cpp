#include "core/host_scene.h"
#include "lightsampler/sampler.h"

namespace lightsampler {

float MapQueries::density(std::uint32_t triangle, float b1, float b2) const {
  return scene_->density(triangle, b1, b2);
}

std::optional<Texel> MapQueries::texel(std::uint32_t triangle, float b1, float b2) const {
  return scene_->texel(triangle, b1, b2);
}

void MapQueries::texel_pieces(std::uint32_t triangle, std::vector<TexelPiece>& out) const {
  scene_->texel_pieces(triangle, out);
}

std::optional<Barycentrics> MapQueries::texel_piece_point(std::uint32_t triangle, std::int64_t cell_x,
                                                          std::int64_t cell_y, float u_fan, float u0,
                                                          float u1) const {
  return scene_->texel_piece_point(triangle, cell_x, cell_y, u_fan, u0, u1);
}

}  // namespace lightsampler
