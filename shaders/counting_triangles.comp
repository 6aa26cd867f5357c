#version 460
#extension GL_GOOGLE_include_directive : require
// Counting, the paper's naive triangle stratification (its "No Rasterization" ablation): one
// thread per triangle, looping over its bounding box's cells. Threads wait for the largest
// triangle of their subgroup; the balanced compute path exists to beat this.
#include "counting.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { CountingPush p; };

void main() {
  for (uint64_t i = thread_index(); i < uint64_t(p.triangle_count); i += thread_count()) {
    if (uint64_at(p.footprint, i).v[0] == 0ul) continue;  // settled by the setup pass
    uint tri = uint(i);
    TexelTriangle t = Triangles(p.triangles).v[tri];
    TriangleCells tt = triangle_cells(t);
    DensityMap map = Maps(p.maps).v[t.map];
    float sum, bound;
    count_cells_of(t, tt, map, p.texels, sum, bound);
    Floats(p.expected).v[tri] = sum;
    Uints(p.max_density).v[tri] = floatBitsToUint(bound);
  }
}
