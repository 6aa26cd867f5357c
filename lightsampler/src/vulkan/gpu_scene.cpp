#include "vulkan/gpu_scene.h"

#include <algorithm>
#include <stdexcept>

#include "core/area_pick.h"
#include "core/texel_pieces.h"
#include "vulkan/layouts.h"

namespace lightsampler::vk {

namespace {

/// The lattice cells of the triangle's bounding box (float corners, as the shaders compute them).
LatticeBox bounding_cells(const core::TexelTriangle& t) {
  const float xs[3] = {t.origin[0], t.origin[0] + t.edge1[0], t.origin[0] + t.edge2[0]};
  const float ys[3] = {t.origin[1], t.origin[1] + t.edge1[1], t.origin[1] + t.edge2[1]};
  return {core::floor_to_int(std::min({xs[0], xs[1], xs[2]})), core::floor_to_int(std::min({ys[0], ys[1], ys[2]})),
          core::floor_to_int(std::max({xs[0], xs[1], xs[2]})), core::floor_to_int(std::max({ys[0], ys[1], ys[2]}))};
}

// Automatic counting (measured on an H100, docs/benchmarks.md): on meshes of at least
// kManyTriangles triangles, a triangle of at most kSmallTriangleCells cells is counted by one
// invocation; larger ones, which would stall their subgroup, go to the balanced cell pass. On
// fewer triangles, one loop per triangle leaves most of a GPU idle, and the cell pass takes all.
constexpr std::uint32_t kSmallTriangleCells = 4096;
constexpr std::uint64_t kManyTriangles = 65536;

void extend(LatticeBox& box, const LatticeBox& cells) {
  if (box.empty()) {
    box = cells;
    return;
  }
  box = {std::min(box.x0, cells.x0), std::min(box.y0, cells.y0), std::max(box.x1, cells.x1),
         std::max(box.y1, cells.y1)};
}

}  // namespace

GpuScene::GpuScene(Context& context, const MeshView& mesh, std::span<const DensityMapView> maps)
    : context_(context), host_(mesh, maps) {
  upload_maps();
  upload_triangles();
  // Plain rejection sampling picks triangles by area: the CDF depends on the mesh alone.
  const auto records = host_.triangles();
  std::vector<double> cdf(records.size());
  double sum = 0;
  for (std::size_t t = 0; t < records.size(); ++t) cdf[t] = sum += records[t].area;
  total_area_ = sum;
  area_cdf_ = context_.create_buffer(cdf.size() * sizeof(double));
  if (!cdf.empty()) context_.upload(area_cdf_, 0, cdf.data(), cdf.size() * sizeof(double));
  const std::vector<std::uint32_t> guide = core::area_guide(cdf);
  area_guide_ = context_.create_buffer(guide.size() * sizeof(std::uint32_t));
  context_.upload(area_guide_, 0, guide.data(), guide.size() * sizeof(std::uint32_t));
}

void GpuScene::update_map(std::size_t index, const DensityMapView& map) {
  const bool resized = host_.update_map(index, map);
  upload_maps();  // texels and records; cheap next to the counting pass that follows
  if (resized) upload_triangles();
}

void GpuScene::upload_maps() {
  std::vector<gpu::DensityMap> records;
  std::vector<float> texels;
  for (const core::DensityMap& m : host_.maps()) {
    if (texels.size() + m.texels.size() > 0xffffffffull)
      throw std::length_error("density maps hold more than 2^32 texels in all");
    records.push_back({std::uint32_t(texels.size()), m.width, m.height, std::uint32_t(m.addressing), m.scale, 0, 0, 0});
    texels.insert(texels.end(), m.texels.begin(), m.texels.end());
  }
  if (map_records_.size() < records.size() * sizeof(gpu::DensityMap) || !map_records_)
    map_records_ = context_.create_buffer(records.size() * sizeof(gpu::DensityMap));
  if (texels_.size() < texels.size() * sizeof(float) || !texels_)
    texels_ = context_.create_buffer(texels.size() * sizeof(float));
  if (!records.empty()) {
    context_.upload(map_records_, 0, records.data(), records.size() * sizeof(gpu::DensityMap));
    context_.upload(texels_, 0, texels.data(), texels.size() * sizeof(float));
  }
}

void GpuScene::upload_triangles() {
  const auto records = host_.triangles();
  const auto texel_triangles = host_.texel_triangles();
  map_boxes_.assign(host_.maps().size(), {0, 0, -1, -1});
  candidate_cells_ = large_triangle_cells_ = 0;
  small_triangle_cells_ = records.size() >= kManyTriangles ? kSmallTriangleCells : 0;
  std::vector<gpu::TexelTriangle> gpu(records.size());
  std::vector<std::uint64_t> piece_offsets(records.size() + 1, 0);
  for (std::size_t t = 0; t < records.size(); ++t) {
    const core::TexelTriangle& tt = texel_triangles[t];
    gpu[t] = {tt.origin[0], tt.origin[1], tt.edge1[0], tt.edge1[1], tt.edge2[0], tt.edge2[1],
              float(records[t].area), tt.map};
    piece_offsets[t + 1] = piece_offsets[t] + (tt.map == kNoMap ? 0 : core::piece_cells(tt).count());
    if (tt.map == kNoMap) continue;
    const LatticeBox cells = bounding_cells(tt);
    extend(map_boxes_[tt.map], cells);
    // The same cells as the shaders' float bounding box, so that a triangle small here is small
    // in the setup pass too.
    const std::uint64_t count = std::uint64_t(cells.x1 - cells.x0 + 1) * std::uint64_t(cells.y1 - cells.y0 + 1);
    candidate_cells_ += count;
    if (count > small_triangle_cells_) large_triangle_cells_ += count;
  }
  if (!triangles_) triangles_ = context_.create_buffer(gpu.size() * sizeof(gpu::TexelTriangle));
  if (!gpu.empty()) context_.upload(triangles_, 0, gpu.data(), gpu.size() * sizeof(gpu::TexelTriangle));
  const VkDeviceSize offset_bytes = piece_offsets.size() * sizeof(std::uint64_t);
  if (!piece_offsets_) piece_offsets_ = context_.create_buffer(offset_bytes);
  context_.upload(piece_offsets_, 0, piece_offsets.data(), offset_bytes);
  piece_cells_ = piece_offsets.back();
}

}  // namespace lightsampler::vk
