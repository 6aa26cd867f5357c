// shaders/texel_pieces.glsl against core/texel_pieces.h: clipped_area, the GLSL clipper's area of
// one (triangle, cell) pair, is the area of the piece the host's walk gives that cell, bit for
// bit, and zero where the walk gives none (on devices whose double arithmetic is IEEE 754's, as
// lavapipe's is).

#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/texel_pieces.h"
#include "sampler_fixtures.h"
#include "shaders/clipped_area.h"
#include "spirv/clipped_area_comp.h"
#include "vulkan/layouts.h"
#include "vulkan_fixture.h"

namespace {

namespace vk = lightsampler::vk;
namespace core = lightsampler::core;
using trs_test::AreaQuery;
using trs_test::ClippedAreaPush;

static_assert(sizeof(AreaQuery) == 16 && sizeof(ClippedAreaPush) == 32);

/// Texel-space triangles: random ones over a few texels and far from the origin, a sliver, one
/// inside a single cell, and one without UV area.
std::vector<core::TexelTriangle> test_triangles() {
  const trs_test::Mesh mesh = trs_test::random_triangles(60, -1.5f, 2.5f, 71);
  const core::DensityMap map{std::vector<float>(7 * 5, 1.0f), 7, 5, lightsampler::Addressing::wrap, 1.0f};
  std::vector<core::TexelTriangle> out;
  for (const core::TriangleRecord& r : core::make_triangle_records(mesh.view(), 1))
    out.push_back(core::make_texel_triangle(r, {&map, 1}));
  out.push_back({{0.1f, 2.5f}, {12.3f, 0.02f}, {6.0f, 0.05f}, 0});
  out.push_back({{3.2f, -4.7f}, {0.3f, 0.1f}, {0.1f, 0.4f}, 0});
  out.push_back({{-2.5f, 1.5f}, {1.0f, 2.0f}, {2.0f, 4.0f}, 0});
  return out;
}

class TexelPiecesShader : public trs_test::VulkanTest {};

TEST_F(TexelPiecesShader, ClippedAreaIsTheHostsPieceArea) {
  const std::vector<core::TexelTriangle> triangles = test_triangles();
  std::vector<AreaQuery> queries;
  std::vector<double> want;
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    std::map<std::pair<std::int64_t, std::int64_t>, double> pieces;
    core::for_each_texel_piece(triangles[t], [&](const core::TexelPiece& p) { pieces[{p.ix, p.iy}] = p.area; });
    // Every cell of the box and a ring of cells around it, where the area is zero.
    const core::PieceCells box = core::piece_cells(triangles[t]);
    for (std::int64_t iy = box.y0 - 1; iy <= box.y1 + 1; ++iy)
      for (std::int64_t ix = box.x0 - 1; ix <= box.x1 + 1; ++ix) {
        queries.push_back({t, int(ix), int(iy), 0});
        const auto it = pieces.find({ix, iy});
        want.push_back(it == pieces.end() ? 0.0 : it->second);
      }
  }
  std::vector<lightsampler::gpu::TexelTriangle> gpu;
  for (const core::TexelTriangle& t : triangles)
    gpu.push_back({t.origin[0], t.origin[1], t.edge1[0], t.edge1[1], t.edge2[0], t.edge2[1], 1.0f, t.map});
  const vk::Buffer tri_buffer = context->create_buffer(gpu.size() * sizeof(gpu[0]));
  const vk::Buffer query_buffer = context->create_buffer(queries.size() * sizeof(AreaQuery));
  const vk::Buffer area_buffer = context->create_buffer(queries.size() * sizeof(double));
  context->upload(tri_buffer, 0, gpu.data(), gpu.size() * sizeof(gpu[0]));
  context->upload(query_buffer, 0, queries.data(), queries.size() * sizeof(AreaQuery));
  const vk::ComputePipeline pipeline =
      context->create_compute(lightsampler::spirv::clipped_area_comp, sizeof(ClippedAreaPush));
  const ClippedAreaPush push{tri_buffer.address(), query_buffer.address(), area_buffer.address(),
                             std::uint32_t(queries.size()), 0};
  vk::Commands cmd = context->begin();
  cmd.dispatch(pipeline, &push, sizeof push,
               std::uint32_t((queries.size() + CLIPPED_AREA_WORKGROUP_SIZE - 1) / CLIPPED_AREA_WORKGROUP_SIZE));
  context->submit(cmd);
  std::vector<double> got(queries.size());
  context->download(area_buffer, 0, got.data(), got.size() * sizeof(double));
  std::size_t pieces = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    ASSERT_EQ(got[i], want[i]) << "triangle " << queries[i].triangle << ", cell " << queries[i].ix << ", "
                               << queries[i].iy;
    pieces += want[i] > 0.0;
  }
  EXPECT_GT(pieces, 300u);
}

}  // namespace
