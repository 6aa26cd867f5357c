#version 460
#extension GL_GOOGLE_include_directive : require
// Counting, compute path: (triangle, lattice cell) candidates balanced across threads whatever
// the triangles' sizes. Candidate c belongs to the first triangle whose inclusive footprint
// prefix sum exceeds c. Each thread takes a run of kCellsPerRun consecutive candidates: one
// binary search per run, then it walks from triangle to triangle, summing locally and adding
// to N-bar_T and D_T^max once per triangle it touched.
#include "counting.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { CountingPush p; };

uint64_t cell_cdf(uint tri) { return uint64_at(p.cell_cdf, tri).v[0]; }

uint owner(uint64_t c) {
  uint lo = 0u, hi = p.triangle_count - 1u;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (cell_cdf(mid) > c) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

void flush(uint tri, float sum, float bound) {
  if (sum > 0.0) atomicAdd(Floats(p.expected).v[tri], sum);
  if (bound > 0.0) atomic_max_float(Uints(p.max_density), tri, bound);
}

void main() {
  if (p.triangle_count == 0u) return;
  uint64_t total = cell_cdf(p.triangle_count - 1u);
  uint64_t runs = (total + kCellsPerRun - 1ul) / kCellsPerRun;
  Triangles triangles = Triangles(p.triangles);
  Maps maps = Maps(p.maps);
  for (uint64_t run = thread_index(); run < runs; run += thread_count()) {
    uint64_t first = run * kCellsPerRun, last = min(first + kCellsPerRun, total);
    uint tri = owner(first);
    uint64_t begin = tri > 0u ? cell_cdf(tri - 1u) : 0ul, end = cell_cdf(tri);
    TexelTriangle t = triangles.v[tri];
    TriangleCells tt = triangle_cells(t);
    DensityMap map = maps.v[t.map];
    // Column and row of the current cell: divided once per triangle, then stepped.
    uint64_t column = (first - begin) % tt.columns, row = (first - begin) / tt.columns;
    float sum = 0.0, bound = 0.0;
    for (uint64_t c = first; c < last; ++c) {
      if (c >= end) {  // the next triangle with cells (empty footprints are skipped)
        flush(tri, sum, bound);
        sum = bound = 0.0;
        tri = owner(c);
        begin = cell_cdf(tri - 1u);
        end = cell_cdf(tri);
        t = triangles.v[tri];
        tt = triangle_cells(t);
        map = maps.v[t.map];
        column = (c - begin) % tt.columns;
        row = (c - begin) / tt.columns;
      }
      float density;
      sum += cell_contribution(t, tt, map, p.texels, tt.first_x + int64_t(column), tt.first_y + int64_t(row), density);
      bound = max(bound, density);
      if (++column == tt.columns) {
        column = 0ul;
        ++row;
      }
    }
    flush(tri, sum, bound);
  }
}
