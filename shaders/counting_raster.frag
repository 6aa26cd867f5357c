#version 460
#extension GL_GOOGLE_include_directive : require
// One fragment per (triangle, lattice cell): the exact overlap of Section 4, times the texel's
// density, into N-bar_T and D_T^max (Algorithm 2, lines 2-8).
#include "counting.glsl"

layout(push_constant) uniform Push { RasterPush p; };
layout(location = 0) in flat uint g_triangle;

void main() {
  uint tri = g_triangle;
  TexelTriangle t = Triangles(p.triangles).v[tri];
  int64_t ix = int64_t(p.origin_x) + int64_t(floor(gl_FragCoord.x));
  int64_t iy = int64_t(p.origin_y) + int64_t(floor(gl_FragCoord.y));
  float density;
  float contribution = cell_contribution(t, triangle_cells(t), Maps(p.maps).v[t.map], p.texels, ix, iy, density);
  accumulate(p.expected, p.max_density, tri, contribution, density, !gl_HelperInvocation);
}
