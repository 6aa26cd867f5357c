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
    float sum = 0.0, bound = 0.0;
    // Rows, then columns: no single loop reaches lavapipe's 65535-iteration limit.
    for (uint64_t row = 0ul; row < tt.rows; ++row)
      for (uint64_t column = 0ul; column < tt.columns; ++column) {
        float density;
        sum += cell_contribution(t, tt, map, p.texels, tt.first_x + int64_t(column), tt.first_y + int64_t(row),
                                 density);
        bound = max(bound, density);
      }
    Floats(p.expected).v[tri] = sum;
    Uints(p.max_density).v[tri] = floatBitsToUint(bound);
  }
}
