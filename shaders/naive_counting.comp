#version 460
#extension GL_GOOGLE_include_directive : require
// Naive triangle stratification's counting (paper, Section 3.2; cpu::naive_count): one
// invocation per triangle walks its texel pieces with the polygon clipper, deliberately, and
// writes N-bar_T, D_T^max and the CDF of its pieces that realization draws from.
#include "texel_pieces.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { CountingPush p; };

void main() {
  for (uint64_t i = thread_index(); i < uint64_t(p.triangle_count); i += thread_count()) {
    uint tri = uint(i);
    TexelTriangle t = Triangles(p.triangles).v[tri];
    PieceSums sums = PieceSums(0.0lf, 0.0);  // of the density over barycentric area
    if (t.map != kNoMap) {
      uint64_t first = uint64_at(p.piece_offsets, i).v[0];
      uint64_t cells = uint64_at(p.piece_offsets, i + 1ul).v[0] - first;
      sums = walk_texel_pieces(t, Maps(p.maps).v[t.map], p.texels, p.piece_cdf + first * 8ul, cells);
    }
    // Barycentric area 1/2 is the triangle's world area.
    Floats(p.expected).v[tri] = float(2.0lf * sums.weight * double(t.area));
    Uints(p.max_density).v[tri] = floatBitsToUint(sums.bound);
  }
}
