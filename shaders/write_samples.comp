#version 460
#extension GL_GOOGLE_include_directive : require
// The floor under realization: writes p.count samples, each to its own place, and does nothing
// else (lightsampler::sample_write_ms).
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { WritePush p; };

void main() {
  for (uint64_t i = thread_index(); i < p.count; i += thread_count())
    Samples(p.samples + i * uint64_t(kSampleBytes)).v[0] = Sample(uint(i), 0.25, 0.25);
}
