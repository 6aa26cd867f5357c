#version 460
#extension GL_GOOGLE_include_directive : require
// Naive triangle stratification's counting (paper, Section 3.2; cpu::naive_count): one
// invocation per triangle walks its texel pieces with the polygon clipper, deliberately, and
// writes N-bar_T, D_T^max and the sum its realization draws pieces from.
#include "texel_pieces.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { CountingPush p; };

void main() {
  for (uint64_t i = thread_index(); i < uint64_t(p.triangle_count); i += thread_count()) {
    uint tri = uint(i);
    TexelTriangle t = Triangles(p.triangles).v[tri];
    double weight = 0.0lf;  // of the density over barycentric area
    float bound = 0.0;
    if (t.map != kNoMap) {
      PieceWalk w = walk_texel_pieces(t, Maps(p.maps).v[t.map], p.texels, false, 0.0lf);
      weight = w.weight;
      bound = w.bound;
    }
    // Barycentric area 1/2 is the triangle's world area.
    Floats(p.expected).v[tri] = float(2.0lf * weight * double(t.area));
    Uints(p.max_density).v[tri] = floatBitsToUint(bound);
    Doubles(p.weights).v[tri] = weight;
  }
}
