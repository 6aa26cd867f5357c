#version 460
#extension GL_GOOGLE_include_directive : require
// Counting, compute path: one thread per (triangle, lattice cell) candidate, balanced across
// threads whatever the triangles' sizes. Candidate c belongs to the first triangle whose
// inclusive footprint prefix sum exceeds c.
#include "counting.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { CountPush p; };

uint owner(uint64_t c) {
  uint lo = 0u, hi = p.triangle_count - 1u;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (uint64_at(p.cell_cdf, mid).v[0] > c) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

void main() {
  if (p.triangle_count == 0u) return;
  uint64_t total = uint64_at(p.cell_cdf, p.triangle_count - 1u).v[0];
  Triangles triangles = Triangles(p.triangles);
  Maps maps = Maps(p.maps);
  for (uint64_t c = thread_index(); c < total; c += thread_count()) {
    uint tri = owner(c);
    uint64_t local_cell = c - (tri > 0u ? uint64_at(p.cell_cdf, tri - 1u).v[0] : 0ul);
    GpuTriangle t = triangles.v[tri];
    TexelTriangle tt = texel_triangle(t);
    int64_t ix = tt.first_x + int64_t(local_cell % tt.columns);
    int64_t iy = tt.first_y + int64_t(local_cell / tt.columns);
    float density;
    float contribution = cell_contribution(t, tt, maps.v[t.map], p.texels, ix, iy, density);
    accumulate(p.expected, p.max_density, tri, contribution, density, true);
  }
}
