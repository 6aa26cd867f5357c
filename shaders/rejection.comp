#version 460
#extension GL_GOOGLE_include_directive : require
// Plain rejection sampling (Algorithm 1): triangle by area (binary search in the area CDF),
// uniform point, accepted against the global bound. Same stream as the CPU backend.
#include "workgroup.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RejectionPush p; };

uint pick_triangle(double target) {
  Doubles cdf = Doubles(p.area_cdf);
  uint lo = 0u, hi = p.triangle_count - 1u;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (cdf.v[mid] > target) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

// One sample per invocation, as in realization.comp (lavapipe's shared loop limiter).
void main() {
  Totals totals = Totals(p.totals);
  uint64_t i = p.first + uint64_t(gl_GlobalInvocationID.x);
  uint64_t tries = 0ul, gave_up = 0ul;
  if (i < totals.t.realized) {
    float bound = uintBitsToFloat(totals.t.max_density_bits);
    double total_area = Doubles(p.area_cdf).v[p.triangle_count - 1u];
    uvec2 key = uvec2(p.key0, p.key1);
    Triangles triangles = Triangles(p.triangles);
    Maps maps = Maps(p.maps);
    uint tri = 0u;
    vec2 b = vec2(0.0);
    bool accepted = false;
    uint attempt = 0u;
    while (!accepted && attempt < p.max_tries) {
      uvec4 u = philox4x32(uvec4(uint(i), uint(i >> 32), attempt, 0u), key);
      tri = pick_triangle(uniform_double(u.x) * total_area);
      b = triangle_map(uniform_float(u.y), uniform_float(u.z));
      ++attempt;
      accepted = uniform_float(u.w) * bound < texel_triangle_density(triangles.v[tri], maps, p.texels, b);
    }
    Samples(p.samples + i * uint64_t(kSampleBytes)).v[0] = Sample(tri, b.x, b.y);
    tries = attempt;
    gave_up = accepted ? 0ul : 1ul;
  }
  count_tries(totals, tries, gave_up);
}
