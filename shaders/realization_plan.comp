#version 460
#extension GL_GOOGLE_include_directive : require
// Sizes realization on the device, so that a frame needs no host read-back: from N (written by
// the rounding pass, or for plain rejection sampling computed here) and the sample buffer's
// capacity, the number of samples to realize and the workgroup count of the realization
// dispatch (vkCmdDispatchIndirect). One invocation.
#include "common.glsl"

layout(local_size_x = 1) in;
layout(push_constant) uniform Push { PlanPush p; };

// Plain rejection sampling's count (core::rejection_sample_count): the target, or N-bar, rounded
// stochastically by the rounding stream's reserved counter; none without density or area.
uint64_t rejection_count(Totals totals) {
  float bound = uintBitsToFloat(totals.t.max_density_bits);
  if (!(bound > 0.0) || !(p.total_area > 0.0lf)) return 0ul;
  // At most 2^63, so the conversion below is defined: a larger N-bar is refused by the host.
  double target = min(p.target >= 0.0lf ? p.target : double(totals.t.expected_total), 9223372036854775808.0lf);
  double whole = floor(target);
  double u = uniform53(philox4x32(uvec4(0xffffffffu, 0u, 0u, 0u), uvec2(p.key0, p.key1)));
  return uint64_t(whole) + (u < target - whole ? 1ul : 0ul);
}

void main() {
  Totals totals = Totals(p.totals);
  if (p.method == kPlanRejection) totals.t.sample_count = rejection_count(totals);
  // N beyond the capacity: the host runs the frame again with room for it (and the scan, chosen
  // for a smaller total, may not hold); realize nothing.
  uint64_t n = totals.t.sample_count <= p.capacity ? totals.t.sample_count : 0ul;
  totals.t.realized = n;
  uint64_t chunks = (n + uint64_t(kSegmentSlots) - 1ul) / uint64_t(kSegmentSlots);
  uint64_t groups = (chunks + uint64_t(kChunksPerWorkgroup) - 1ul) / uint64_t(kChunksPerWorkgroup);
  Uints args = Uints(p.indirect);
  args.v[0] = uint(min(groups, uint64_t(p.max_workgroups)));
  args.v[1] = 1u;
  args.v[2] = 1u;
}
