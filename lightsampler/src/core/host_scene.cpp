#include "core/host_scene.h"

#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/piece_draw.h"
#include "core/texel_pieces.h"
#include "core/validate.h"

namespace lightsampler::core {

namespace {

DensityMap copy_map(const DensityMapView& view) {
  return {{view.texels.begin(), view.texels.end()}, view.width, view.height, view.addressing, view.scale};
}

}  // namespace

std::vector<DensityMap> checked_maps(const MeshView& mesh, std::span<const DensityMapView> maps) {
  validate_mesh(mesh, maps.size());
  std::vector<DensityMap> copies;
  copies.reserve(maps.size());
  for (std::size_t i = 0; i < maps.size(); ++i) {
    validate_map(maps[i], i);
    copies.push_back(copy_map(maps[i]));
  }
  return copies;
}

HostScene::HostScene(const MeshView& mesh, std::span<const DensityMapView> maps) : maps_(checked_maps(mesh, maps)) {
  triangles_ = make_triangle_records(mesh, maps.size());
  texel_triangles_.resize(triangles_.size());
  build_texel_triangles(kAllMaps);
}

bool HostScene::update_map(std::size_t index, const DensityMapView& map) {
  if (index >= maps_.size())
    throw std::out_of_range("density map " + std::to_string(index) + " does not exist (" +
                            std::to_string(maps_.size()) + " maps)");
  validate_map(map, index);
  const bool resized = map.width != maps_[index].width || map.height != maps_[index].height;
  maps_[index] = copy_map(map);
  if (resized) build_texel_triangles(index);
  return resized;
}

const TexelTriangle& HostScene::texel_triangle(std::uint32_t triangle) const {
  if (triangle >= texel_triangles_.size())
    throw std::out_of_range("triangle " + std::to_string(triangle) + " does not exist");
  return texel_triangles_[triangle];
}

float HostScene::density(std::uint32_t triangle, float b1, float b2) const {
  return texel_triangle_density(texel_triangle(triangle), maps_, b1, b2);
}

std::optional<Texel> HostScene::texel(std::uint32_t triangle, float b1, float b2) const {
  return texel_triangle_texel(texel_triangle(triangle), maps_, b1, b2);
}

namespace {

lightsampler::TexelPiece public_piece(const TexelPiece& piece, const DensityMap& map, std::uint32_t index) {
  lightsampler::TexelPiece out{piece.ix, piece.iy, cell_texel(map, index, piece.ix, piece.iy),
                               cell_density(map, piece.ix, piece.iy), 2.0 * piece.area,
                               std::uint32_t(piece.polygon.n), {}};
  for (int i = 0; i < piece.polygon.n; ++i) out.vertices[i] = piece.polygon.v[i];
  return out;
}

}  // namespace

void HostScene::texel_pieces(std::uint32_t triangle, std::vector<lightsampler::TexelPiece>& out) const {
  out.clear();
  const TexelTriangle& t = texel_triangle(triangle);
  if (t.map == kNoMap) return;
  const DensityMap& map = maps_[t.map];
  // Dark cells are not clipped: a sparse map's triangle has few lit ones.
  for_each_texel_piece(
      t, [&](const TexelPiece& piece) { out.push_back(public_piece(piece, map, t.map)); },
      [&](std::int64_t ix, std::int64_t iy) { return cell_density(map, ix, iy) > 0.0f; });
}

std::optional<Barycentrics> HostScene::texel_piece_point(std::uint32_t triangle, std::int64_t cell_x,
                                                         std::int64_t cell_y, float u_fan, float u0,
                                                         float u1) const {
  const TexelTriangle& t = texel_triangle(triangle);
  if (t.map == kNoMap) return std::nullopt;
  const std::optional<TexelPiece> piece = core::texel_piece(t, cell_x, cell_y);
  if (!piece) return std::nullopt;
  const auto [b1, b2] = point_in(piece->polygon, piece->area, u_fan, u0, u1);
  return Barycentrics{float(b1), float(b2)};
}

void HostScene::build_texel_triangles(std::size_t map) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles_.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        if (map == kAllMaps || triangles_[i].map == map)
                          texel_triangles_[i] = make_texel_triangle(triangles_[i], maps_);
                    });
}

}  // namespace lightsampler::core
