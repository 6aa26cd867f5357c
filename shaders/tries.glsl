// The realization passes' tally of candidates tried and samples that gave up, reduced per
// subgroup, then per workgroup through shared memory: one pair of atomics per workgroup.
// Call at the top level of main, where the whole workgroup arrives (it holds a barrier).
#ifndef LIGHTSAMPLER_TRIES_GLSL
#define LIGHTSAMPLER_TRIES_GLSL

#include "common.glsl"

// One slot per subgroup; a workgroup has at most kWorkgroupSize of them.
shared uint64_t subgroup_tries[kWorkgroupSize];
shared uint64_t subgroup_gave_up[kWorkgroupSize];

void count_tries(Totals totals, uint64_t tries, uint64_t gave_up) {
  tries = subgroupAdd(tries);
  gave_up = subgroupAdd(gave_up);
  if (subgroupElect()) {
    subgroup_tries[gl_SubgroupID] = tries;
    subgroup_gave_up[gl_SubgroupID] = gave_up;
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    uint64_t all_tries = 0ul, all_gave_up = 0ul;
    for (uint s = 0u; s < gl_NumSubgroups; ++s) {
      all_tries += subgroup_tries[s];
      all_gave_up += subgroup_gave_up[s];
    }
    if (all_tries > 0ul) atomicAdd(totals.t.candidates, all_tries);
    if (all_gave_up > 0ul) atomicAdd(totals.t.exhausted, all_gave_up);
  }
}

#endif
