// Reductions over a workgroup: per subgroup, then across the subgroups through shared memory,
// so that a pass adds to the frame's totals with one atomic per workgroup. Each returns the
// result to invocation 0 (gl_LocalInvocationIndex == 0) only. Call them where the whole
// workgroup arrives (they hold barriers): at the top level of main, after any loops.
#ifndef LIGHTSAMPLER_WORKGROUP_GLSL
#define LIGHTSAMPLER_WORKGROUP_GLSL

#include "common.glsl"

// One slot per subgroup; a workgroup has at most kWorkgroupSize of them.
shared uint64_t subgroup_values[kWorkgroupSize];

// The subgroups' partial results, gathered: `partial` is each subgroup's reduction.
void gather_subgroups(uint64_t partial) {
  barrier();  // the slots' previous use is over
  if (subgroupElect()) subgroup_values[gl_SubgroupID] = partial;
  barrier();
}

uint64_t workgroup_add(uint64_t value) {
  gather_subgroups(subgroupAdd(value));
  uint64_t sum = 0ul;
  if (gl_LocalInvocationIndex == 0u)
    for (uint s = 0u; s < gl_NumSubgroups; ++s) sum += subgroup_values[s];
  return sum;
}

float workgroup_add(float value) {
  gather_subgroups(uint64_t(floatBitsToUint(subgroupAdd(value))));
  float sum = 0.0;
  if (gl_LocalInvocationIndex == 0u)
    for (uint s = 0u; s < gl_NumSubgroups; ++s) sum += uintBitsToFloat(uint(subgroup_values[s]));
  return sum;
}

float workgroup_max(float value) {
  gather_subgroups(uint64_t(floatBitsToUint(subgroupMax(value))));
  float largest = 0.0;
  if (gl_LocalInvocationIndex == 0u)
    for (uint s = 0u; s < gl_NumSubgroups; ++s) largest = max(largest, uintBitsToFloat(uint(subgroup_values[s])));
  return largest;
}

// Adds an invocation's candidates and exhausted samples to the frame's totals.
void count_tries(Totals totals, uint64_t tries, uint64_t gave_up) {
  tries = workgroup_add(tries);
  gave_up = workgroup_add(gave_up);
  if (gl_LocalInvocationIndex == 0u) {
    if (tries > 0ul) atomicAdd(totals.t.candidates, tries);
    if (gave_up > 0ul) atomicAdd(totals.t.exhausted, gave_up);
  }
}

#endif
