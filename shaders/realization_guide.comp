#version 460
#extension GL_GOOGLE_include_directive : require
// Realization's inverse CDF (inverse_cdf.glsl), built after the scan when a frame asks for it:
// guide[b] for the T + 1 buckets b in [0, T], from the frame's N.
#include "inverse_cdf.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RealizationPush p; };

void main() {
  uint64_t n = Totals(p.totals).t.sample_count;
  uint64_t bucket = guide_bucket(n, p.triangle_count);
  uint last = p.triangle_count - 1u;
  for (uint64_t b = thread_index(); b <= uint64_t(p.triangle_count); b += thread_count()) {
    uint64_t first = b * bucket;  // at most N + T: no overflow
    Uints(p.guide).v[uint(b)] = first < n ? first_above(p.cdf, first, 0u, last) : last;
  }
}
