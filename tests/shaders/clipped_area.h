// Push constants and queries of clipped_area.comp, shared by the shader and
// texel_pieces_shader_test.cpp.
#ifndef TRS_TEST_CLIPPED_AREA_H
#define TRS_TEST_CLIPPED_AREA_H

#ifdef __cplusplus
#include <cstdint>
namespace trs_test {
using uint = std::uint32_t;
using std::uint64_t;
#endif

#define CLIPPED_AREA_WORKGROUP_SIZE 64

/// One (triangle, lattice cell) pair.
struct AreaQuery {
  uint triangle;
  int ix;
  int iy;
  uint pad;
};

struct ClippedAreaPush {
  uint64_t triangles;  // TexelTriangle[]
  uint64_t queries;    // AreaQuery[count]
  uint64_t areas;      // double[count]: clipped_area of each query
  uint count;
  uint pad;
};

#ifdef __cplusplus
}  // namespace trs_test
#endif
#endif
