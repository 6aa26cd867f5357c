#version 460
#extension GL_GOOGLE_include_directive : require
// Scaling to the target and stochastic rounding (Algorithm 2, lines 12-14): N_T is floor(x) or
// floor(x) + 1 with E[N_T] = x = scale * N-bar_T. Same stream and arithmetic (double, 53-bit
// uniform) as the CPU backend's round_counts.
#include "workgroup.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RoundingPush p; };

void main() {
  Totals totals = Totals(p.totals);
  double total = double(totals.t.expected_total);
  double scale = p.target < 0.0 ? 1.0 : (total > 0.0 ? p.target / total : 0.0);
  uvec2 key = uvec2(p.key0, p.key1);
  uint64_t sum = 0ul;
  for (uint64_t i = thread_index(); i < uint64_t(p.triangle_count); i += thread_count()) {
    // At most 2^63, so the conversion below is defined: a larger total (a float sum that
    // overflowed) is refused by the host after this pass, whatever the counts.
    double x = min(scale * double(Floats(p.expected).v[uint(i)]), 9223372036854775808.0lf);
    double whole = floor(x);
    uvec4 r = philox4x32(uvec4(uint(i), 0u, 0u, 0u), key);
    double u = uniform53(r);
    uint64_t count = uint64_t(whole) + (u < x - whole ? 1ul : 0ul);
    uint64_at(p.counts, i).v[0] = count;
    sum += count;
  }
  sum = workgroup_add(sum);
  if (gl_LocalInvocationIndex == 0u && sum > 0ul) atomicAdd(totals.t.sample_count, sum);
}
