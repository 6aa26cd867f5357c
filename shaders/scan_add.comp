#version 460
#extension GL_GOOGLE_include_directive : require
// Ordered inclusive scan, last level: adds to each element the inclusive scan of the blocks
// before its own (block_sums, already scanned).
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { ScanPush p; };

void main() {
  for (uint64_t i = thread_index(); i < p.count; i += thread_count()) {
    uint64_t block = i / kWorkgroupSize;
    if (block > 0ul) uint64_at(p.result, i).v[0] += uint64_at(p.block_sums, block - 1ul).v[0];
  }
}
