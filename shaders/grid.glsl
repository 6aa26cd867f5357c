// Grid-stride loops for compute passes: thread thread_index() handles elements
// thread_index() + k * thread_count(), so a bounded dispatch covers any element count.
#ifndef LIGHTSAMPLER_GRID_GLSL
#define LIGHTSAMPLER_GRID_GLSL

uint64_t thread_index() { return uint64_t(gl_GlobalInvocationID.x); }
// Every compute pass runs kWorkgroupSize invocations per workgroup. (gl_WorkGroupSize would
// read (1, 1, 1) here: this file comes before the shader's local_size declaration.)
uint64_t thread_count() { return uint64_t(gl_NumWorkGroups.x) * uint64_t(kWorkgroupSize); }

#endif
