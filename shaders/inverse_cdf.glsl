// Finding a sample's triangle in the counts' inclusive CDF: a binary search, narrowed, in the
// paper's "Inverse CDF" ablation, by a guide table (an inverse CDF). Sample indices [0, N) fall
// into buckets of guide_bucket(N, T) indices; guide[b] is the processing index of bucket b's
// first sample (T - 1 for a bucket past N), so a sample of bucket b has its index between
// guide[b] and guide[b + 1], and the narrowed search finds the same one.
#ifndef LIGHTSAMPLER_INVERSE_CDF_GLSL
#define LIGHTSAMPLER_INVERSE_CDF_GLSL

#include "common.glsl"

// Sample indices per bucket: at least one, and at most `triangles` buckets below `samples`.
uint64_t guide_bucket(uint64_t samples, uint triangles) {
  return max((samples + uint64_t(triangles) - 1ul) / uint64_t(triangles), 1ul);
}

#endif
