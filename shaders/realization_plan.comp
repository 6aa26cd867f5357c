#version 460
#extension GL_GOOGLE_include_directive : require
// Sizes realization on the device, so that a frame needs no host read-back: from N (written by
// the rounding pass) and the sample buffer's capacity, the number of samples to realize and the
// workgroup counts of each realization dispatch (vkCmdDispatchIndirect). One invocation.
#include "common.glsl"

layout(local_size_x = 1) in;
layout(push_constant) uniform Push { PlanPush p; };

void main() {
  Totals totals = Totals(p.totals);
  // N beyond the capacity: the host runs the frame again with room for it (and the scan, chosen
  // for a smaller total, may not hold); realize nothing.
  uint64_t n = totals.t.sample_count <= p.capacity ? totals.t.sample_count : 0ul;
  totals.t.realized = n;
  for (uint k = 0u; k < p.dispatches; ++k) {
    uint64_t first = uint64_t(k) * p.per_dispatch;
    uint64_t count = n > first ? min(n - first, p.per_dispatch) : 0ul;
    Uints args = Uints(p.indirect);
    args.v[3u * k] = uint((count + uint64_t(kWorkgroupSize) - 1ul) / uint64_t(kWorkgroupSize));
    args.v[3u * k + 1u] = 1u;
    args.v[3u * k + 2u] = 1u;
  }
}
