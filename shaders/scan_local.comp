#version 460
#extension GL_GOOGLE_include_directive : require
// Ordered inclusive scan, first level: each block of kWorkgroupSize elements is scanned in
// shared memory and its total written to block_sums. The host scans block_sums the same way and
// scan_add.comp adds each block's offset.
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { ScanPush p; };

shared uint64_t partial[2][kWorkgroupSize];

void main() {
  uint lane = gl_LocalInvocationID.x;
  uint64_t blocks = (p.count + kWorkgroupSize - 1ul) / kWorkgroupSize;
  // The loop bound is uniform over the workgroup, so the barriers inside are too.
  for (uint64_t block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
    uint64_t i = block * kWorkgroupSize + lane;
    partial[0][lane] = i < p.count ? uint64_at(p.source, i).v[0] : 0ul;
    barrier();
    uint from = 0u;
    for (uint offset = 1u; offset < kWorkgroupSize; offset <<= 1) {  // Hillis-Steele
      uint64_t v = partial[from][lane];
      if (lane >= offset) v += partial[from][lane - offset];
      partial[1u - from][lane] = v;
      barrier();
      from = 1u - from;
    }
    if (i < p.count) uint64_at(p.result, i).v[0] = partial[from][lane];
    if (lane == kWorkgroupSize - 1u) uint64_at(p.block_sums, block).v[0] = partial[from][lane];
    barrier();
  }
}
