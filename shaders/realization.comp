#version 460
#extension GL_GOOGLE_include_directive : require
// Realization (Algorithm 4): one thread per sample. Binary search in the (unordered) CDF,
// inverse permutation, then candidates from Heitz's map accepted against D_T^max. Random
// numbers keyed by (triangle, rank within the triangle, try), as in the CPU backend.
#include "workgroup.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizationPush p; };

uint processing_index(uint64_t sample_index) {
  uint lo = 0u, hi = p.triangle_count - 1u;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (uint64_at(p.cdf, mid).v[0] > sample_index) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

// One sample per invocation, no grid-stride loop around the rejection loop: Mesa's llvmpipe
// (lavapipe) ends loops after about 65535 iterations with a counter that nested loops share, so
// a long rejection loop would cut short the loop around it. Large counts take several dispatches
// (`first`); on lavapipe the host also keeps max_tries well under that limit (device_max_tries).
void main() {
  Totals totals = Totals(p.totals);
  uint64_t i = p.first + uint64_t(gl_GlobalInvocationID.x);
  uint64_t tries = 0ul, gave_up = 0ul;
  if (i < totals.t.realized) {
    uint slot = processing_index(i);
    uint tri = Uints(p.inverse).v[slot];
    uint64_t rank = i - (slot > 0u ? uint64_at(p.cdf, slot - 1u).v[0] : 0ul);
    TexelTriangle t = Triangles(p.triangles).v[tri];
    DensityMap map = Maps(p.maps).v[t.map];
    float bound = uintBitsToFloat(Uints(p.max_density).v[tri]);
    uvec2 key = uvec2(p.key0, p.key1);
    vec2 b = vec2(0.0);
    bool accepted = false;
    uint attempt = 0u;
    // A while loop with its flag set before it: a do-while left `accepted` wrong after the loop
    // on lavapipe.
    while (!accepted && attempt < p.max_tries) {
      uvec4 u = philox4x32(uvec4(tri, uint(rank), uint(rank >> 32), attempt), key);
      b = triangle_map(uniform_float(u.x), uniform_float(u.y));
      vec2 point = texel_space_point(t, b);
      ++attempt;
      accepted = uniform_float(u.z) * bound < point_density(map, p.texels, point.x, point.y);
    }
    Samples(p.samples + i * uint64_t(kSampleBytes)).v[0] = Sample(tri, b.x, b.y);
    tries = attempt;
    gave_up = accepted ? 0ul : 1ul;
  }
  count_tries(totals, tries, gave_up);
}
