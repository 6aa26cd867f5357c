#version 460
#extension GL_GOOGLE_include_directive : require
// Unordered cumulative sum (Algorithm 3): one 64-bit atomic add reserves, at once, a subgroup's
// output slots (high bits: processing index) and its share of the sum (low bits). The subgroup
// reduces first, so one atomic serves all its lanes (Section 5).
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { ScanPush p; };

void main() {
  uint64_t sum_mask = (1ul << p.sum_bits) - 1ul;
  for (uint64_t i = thread_index(); i < p.count; i += thread_count()) {
    uint64_t element = uint64_at(p.source, i).v[0];
    uint64_t prefix = subgroupExclusiveAdd(element);
    uint64_t subgroup_sum = subgroupAdd(element);
    uvec4 lanes = subgroupBallot(true);
    uint64_t packed = 0ul;
    if (subgroupElect())
      packed = atomicAdd(Totals(p.totals).t.scan_counter,
                         subgroup_sum + (uint64_t(subgroupBallotBitCount(lanes)) << p.sum_bits));
    packed = subgroupBroadcastFirst(packed);
    uint64_t slot = (packed >> p.sum_bits) + uint64_t(subgroupBallotExclusiveBitCount(lanes));
    uint64_at(p.result, slot).v[0] = (packed & sum_mask) + prefix + element;
    Uints(p.inverse).v[uint(slot)] = uint(i);
  }
}
