#version 460
#extension GL_GOOGLE_include_directive : require
// N-bar: the sum of the per-triangle expected counts (float atomics, order unspecified), one
// atomic per workgroup, or per invocation without kSubgroupReduction.
#include "workgroup.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { CountingPush p; };

void main() {
  float sum = 0.0;
  for (uint64_t i = thread_index(); i < uint64_t(p.triangle_count); i += thread_count())
    sum += Floats(p.expected).v[uint(i)];
  if (kSubgroupReduction) sum = workgroup_add(sum);  // a uniform condition: its barriers are reached
  if ((!kSubgroupReduction || gl_LocalInvocationIndex == 0u) && sum > 0.0)
    atomicAdd(Totals(p.totals).t.expected_total, sum);
}
