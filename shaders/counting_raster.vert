#version 460
#extension GL_GOOGLE_include_directive : require
// Counting, raster path: triangles drawn in texel space (UVs times the map's size), the viewport
// covering one tile of the lattice. No vertex buffer: corners are fetched by gl_VertexIndex.
// Triangles of other maps, and those the setup pass settled (footprint zero), collapse to one
// point outside the viewport: clipped, and skipped by the dilation.
#include "common.glsl"

layout(push_constant) uniform Push { RasterPush p; };
layout(location = 0) out flat uint v_triangle;

void main() {
  uint tri = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
  TexelTriangle t = Triangles(p.triangles).v[tri];
  vec2 position = vec2(t.origin_x, t.origin_y);
  if (corner == 1u) position += vec2(t.edge1_x, t.edge1_y);
  if (corner == 2u) position += vec2(t.edge2_x, t.edge2_y);
  vec2 ndc = (position - vec2(p.origin_x, p.origin_y)) / vec2(p.width, p.height) * 2.0 - 1.0;
  bool counted_here = t.map == p.map && uint64_at(p.footprint, tri).v[0] != 0ul;
  gl_Position = counted_here ? vec4(ndc, 0.0, 1.0) : vec4(-2.0, -2.0, 0.0, 1.0);
  v_triangle = tri;
}
