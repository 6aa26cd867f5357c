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

// An invocation's tries and slots of a realization pass: the candidates (or attempts) it tried,
// its slots filled after max_tries rejections in a row, and its slots drawn exactly after
// TRS's rejection stopped.
struct WalkTally {
  uint64_t candidates;
  uint64_t exhausted;
  uint64_t exact;
};

// Adds an invocation's tally to the frame's totals.
void count_tries(Totals totals, WalkTally tally) {
  uint64_t candidates = workgroup_add(tally.candidates);
  uint64_t exhausted = workgroup_add(tally.exhausted);
  uint64_t exact = workgroup_add(tally.exact);
  if (gl_LocalInvocationIndex == 0u) {
    if (candidates > 0ul) atomicAdd(totals.t.candidates, candidates);
    if (exhausted > 0ul) atomicAdd(totals.t.exhausted, exhausted);
    if (exact > 0ul) atomicAdd(totals.t.exact, exact);
  }
}

#endif
