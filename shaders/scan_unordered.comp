#version 460
#extension GL_GOOGLE_include_directive : require
// Unordered cumulative sum (Algorithm 3): one 64-bit atomic add reserves, at once, a subgroup's
// output slots (high bits: processing index) and its share of the sum (low bits). The subgroup
// reduces first, so one atomic serves all its lanes (Section 5); without kSubgroupReduction
// each lane reserves its own slot.
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { ScanPush p; };

// This invocation's processing index and the sum of the elements processed before it, from the
// packed counter. Call with whole subgroups (kSubgroupReduction is a constant: both branches are
// uniform).
void reserve(bool live, uint64_t element, out uint64_t slot, out uint64_t before) {
  uint64_t sum_mask = (1ul << p.sum_bits) - 1ul;  // sum_bits is at most 63 (the host's choice)
  uint64_t packed = 0ul;
  if (kSubgroupReduction) {
    uint64_t prefix = subgroupExclusiveAdd(element);
    uint64_t subgroup_sum = subgroupAdd(element);
    uvec4 lanes = subgroupBallot(live);
    if (subgroupElect())
      packed = atomicAdd(Totals(p.totals).t.scan_counter,
                         subgroup_sum + (uint64_t(subgroupBallotBitCount(lanes)) << p.sum_bits));
    packed = subgroupBroadcastFirst(packed);
    slot = (packed >> p.sum_bits) + uint64_t(subgroupBallotExclusiveBitCount(lanes));
    before = (packed & sum_mask) + prefix;
  } else {
    if (live) packed = atomicAdd(Totals(p.totals).t.scan_counter, element + (1ul << p.sum_bits));
    slot = packed >> p.sum_bits;
    before = packed & sum_mask;
  }
}

// The loop runs the same number of times on every invocation of a workgroup (its bound steps
// by whole workgroups), so the subgroup operations inside see whole subgroups; `live` marks the
// invocations that have an element.
void main() {
  uint64_t group_first = uint64_t(gl_WorkGroupID.x) * kWorkgroupSize;
  for (uint64_t base = group_first; base < p.count; base += thread_count()) {
    uint64_t i = base + gl_LocalInvocationID.x;
    bool live = i < p.count;
    uint64_t element = live ? uint64_at(p.source, i).v[0] : 0ul;
    uint64_t slot, before;
    reserve(live, element, slot, before);
    // A total past the packed word's sum bits (a frame the host runs again with the ordered
    // scan) spills into the index: never write outside the arrays.
    if (live && slot < p.count) {
      uint64_at(p.result, slot).v[0] = before + element;
      Uints(p.inverse).v[uint(slot)] = uint(i);
    }
  }
}
