#version 460
// clipped_area (shaders/texel_pieces.glsl) of each query: one (triangle, lattice cell) pair per
// invocation.
#extension GL_GOOGLE_include_directive : require

#include "../../shaders/texel_pieces.glsl"
#include "clipped_area.h"

layout(local_size_x = CLIPPED_AREA_WORKGROUP_SIZE) in;
layout(push_constant) uniform Push { ClippedAreaPush p; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Queries { AreaQuery v[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= p.count) return;
  AreaQuery q = Queries(p.queries).v[i];
  TexelTriangle t = Triangles(p.triangles).v[q.triangle];
  Doubles(p.areas).v[i] = clipped_area(t, int64_t(q.ix), int64_t(q.iy));
}
