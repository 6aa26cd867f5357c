#pragma once
// The mesh and density maps resident on the device, uploaded once; a map update re-uploads its
// texels (and, when its size changes, the texel-space triangles that use it).

#include <span>
#include <vector>

#include "core/host_scene.h"
#include "vulkan/context.h"

namespace lightsampler::vk {

/// Lattice cells [x0, x1] x [y0, y1] that a map's triangles touch (texel space, unbounded).
struct LatticeBox {
  std::int64_t x0, y0, x1, y1;
  bool empty() const { return x1 < x0; }
};

class GpuScene {
 public:
  GpuScene(Context& context, const MeshView& mesh, std::span<const DensityMapView> maps);

  void update_map(std::size_t index, const DensityMapView& map);

  const core::HostScene& host() const { return host_; }
  std::uint32_t triangle_count() const { return std::uint32_t(host_.triangles().size()); }
  double total_area() const { return total_area_; }
  std::span<const LatticeBox> map_boxes() const { return map_boxes_; }
  /// An upper bound of the counting pass's candidate cells (every mapped triangle's bounding
  /// box), to size its dispatch: it changes only with the geometry and the maps' sizes.
  std::uint64_t candidate_cells() const { return candidate_cells_; }
  /// Automatic counting: triangles of at most this many cells are counted one invocation each
  /// (0: none, on meshes too small to fill a GPU that way), and the candidate cells of the others.
  std::uint32_t small_triangle_cells() const { return small_triangle_cells_; }
  std::uint64_t large_triangle_cells() const { return large_triangle_cells_; }

  VkDeviceAddress triangles() const { return triangles_.address(); }
  VkDeviceAddress map_records() const { return map_records_.address(); }
  VkDeviceAddress texels() const { return texels_.address(); }
  VkDeviceAddress area_cdf() const { return area_cdf_.address(); }
  VkDeviceAddress area_guide() const { return area_guide_.address(); }
  /// Naive stratification: uint64[T + 1], where each triangle's lattice cells (core::piece_cells,
  /// none without a map) start in one array of all of them, and how many there are.
  VkDeviceAddress piece_offsets() const { return piece_offsets_.address(); }
  std::uint64_t piece_cells() const { return piece_cells_; }

 private:
  void upload_maps();
  void upload_triangles();

  Context& context_;
  core::HostScene host_;
  std::vector<LatticeBox> map_boxes_;
  std::uint64_t candidate_cells_ = 0;
  std::uint32_t small_triangle_cells_ = 0;
  std::uint64_t large_triangle_cells_ = 0;
  Buffer triangles_, map_records_, texels_, area_cdf_, area_guide_, piece_offsets_;
  double total_area_ = 0;
  std::uint64_t piece_cells_ = 0;
};

}  // namespace lightsampler::vk
