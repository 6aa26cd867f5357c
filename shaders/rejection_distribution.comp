#version 460
#extension GL_GOOGLE_include_directive : require
// Plain rejection sampling's bound D_M^max: the largest scaled texel of one map (run per map).
#include "workgroup.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RejectionPush p; };

void main() {
  DensityMap map = Maps(p.maps).v[p.map];
  float largest = 0.0;
  for (uint64_t i = thread_index(); i < uint64_t(p.texel_count); i += thread_count())
    largest = max(largest, Floats(p.texels).v[map.offset + uint(i)] * map.scale);
  largest = workgroup_max(largest);
  if (gl_LocalInvocationIndex == 0u && largest > 0.0)
    atomicMax(Totals(p.totals).t.max_density_bits, floatBitsToUint(largest));
}
