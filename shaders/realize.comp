#version 460
#extension GL_GOOGLE_include_directive : require
// Realization (Algorithm 4): one thread per sample. Binary search in the (unordered) CDF,
// inverse permutation, then candidates from Heitz's map accepted against D_T^max. Random
// numbers keyed by (triangle, rank within the triangle, try), as in the CPU backend.
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizePush p; };

uint processing_index(uint64_t sample_index) {
  uint lo = 0u, hi = p.triangle_count - 1u;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (uint64_at(p.cdf, mid).v[0] > sample_index) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

void main() {
  Totals totals = Totals(p.totals);
  uint64_t n = totals.t.sample_count;
  uvec2 key = uvec2(p.key0, p.key1);
  Triangles triangles = Triangles(p.triangles);
  Maps maps = Maps(p.maps);
  uint64_t tries = 0ul, gave_up = 0ul;
  for (uint64_t i = thread_index(); i < n; i += thread_count()) {
    uint slot = processing_index(i);
    uint tri = Uints(p.inverse).v[slot];
    uint64_t rank = i - (slot > 0u ? uint64_at(p.cdf, slot - 1u).v[0] : 0ul);
    GpuTriangle t = triangles.v[tri];
    GpuMap map = maps.v[t.map];
    float bound = uintBitsToFloat(Uints(p.max_density).v[tri]);
    vec2 b = vec2(0.0);
    bool accepted = false;
    uint attempt = 0u;
    // A while loop with its flag set before it: a do-while left `accepted` wrong after the loop
    // on lavapipe (the exhausted tally went astray while the samples stayed right).
    while (!accepted && attempt < p.max_tries) {
      uvec4 u = philox4x32(uvec4(tri, uint(rank), uint(rank >> 32), attempt), key);
      b = triangle_map(uniform_float(u.x), uniform_float(u.y));
      // precise: no fused multiply-add, so the texel read is the CPU backend's, bit for bit.
      precise float x = t.origin_x + b.x * t.edge1_x + b.y * t.edge2_x;
      precise float y = t.origin_y + b.x * t.edge1_y + b.y * t.edge2_y;
      ++attempt;
      accepted = uniform_float(u.z) * bound < point_density(map, p.texels, x, y);
    }
    Samples(p.samples + i * 12ul).v[0] = GpuSample(tri, b.x, b.y);
    tries += attempt;
    gave_up += accepted ? 0ul : 1ul;
  }
  tries = subgroupAdd(tries);
  gave_up = subgroupAdd(gave_up);
  if (subgroupElect()) {
    if (tries > 0ul) atomicAdd(totals.t.candidates, tries);
    if (gave_up > 0ul) atomicAdd(totals.t.exhausted, gave_up);
  }
}
