#version 460
#extension GL_GOOGLE_include_directive : require
// Counting, first pass: clears the per-triangle results and settles the triangles that need no
// cell enumeration (no map, no world area, UV-degenerate, or inside one lattice cell). With
// automatic counting it also counts the triangles of at most p.small_cells cells, one invocation
// each (the per-triangle path, at its best on small triangles). The others get their
// bounding-box cell count, the footprint a later pass enumerates. With p.stale_maps, only the
// triangles of the maps marked there are counted; the others keep their results and get no
// footprint, so that the later passes skip them too.
#include "counting.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { CountingPush p; };

void main() {
  Triangles triangles = Triangles(p.triangles);
  Maps maps = Maps(p.maps);
  for (uint64_t i = thread_index(); i < uint64_t(p.triangle_count); i += thread_count()) {
    uint tri = uint(i);
    TexelTriangle t = triangles.v[tri];
    if (p.stale_maps != 0ul && (t.map == kNoMap || Uints(p.stale_maps).v[t.map] == 0u)) {
      uint64_at(p.footprint, i).v[0] = 0ul;
      continue;
    }
    float expected = 0.0, bound = 0.0;
    uint64_t cells = 0ul;
    if (t.map != kNoMap && t.area > 0.0) {
      DensityMap map = maps.v[t.map];
      TriangleCells tt = triangle_cells(t);
      if (uv_degenerate(t) || (tt.columns == 1ul && tt.rows == 1ul)) {
        // Constant density over the triangle: read where the realization pass reads.
        bound = uv_degenerate(t) ? point_density(map, p.texels, t.origin_x, t.origin_y)
                                 : cell_density(map, p.texels, tt.first_x, tt.first_y);
        expected = bound * t.area;
      } else {
        cells = tt.columns * tt.rows;
        if (cells <= uint64_t(p.small_cells)) {  // automatic: a few cells, counted here at once
          count_cells_of(t, tt, map, p.texels, expected, bound);
          cells = 0ul;
        }
      }
    }
    Floats(p.expected).v[tri] = expected;
    Uints(p.max_density).v[tri] = floatBitsToUint(bound);
    uint64_at(p.footprint, i).v[0] = cells;
  }
}
