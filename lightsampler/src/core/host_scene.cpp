#include "core/host_scene.h"

#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/validate.h"

namespace lightsampler::core {

namespace {

DensityMap copy_map(const DensityMapView& view) {
  return {{view.texels.begin(), view.texels.end()}, view.width, view.height, view.addressing, view.scale};
}

}  // namespace

HostScene::HostScene(const MeshView& mesh, std::span<const DensityMapView> maps) {
  validate_mesh(mesh, maps.size());
  for (std::size_t i = 0; i < maps.size(); ++i) {
    validate_map(maps[i], i);
    maps_.push_back(copy_map(maps[i]));
  }
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

void HostScene::build_texel_triangles(std::size_t map) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles_.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        if (map == kAllMaps || triangles_[i].map == map)
                          texel_triangles_[i] = make_texel_triangle(triangles_[i], maps_);
                    });
}

}  // namespace lightsampler::core
