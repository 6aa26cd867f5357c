// Shared by every pass: extensions, buffer types reached by device address, and the GPU twins
// of the core's texel lookup (core/density.h, core/geometry.h) and sampling helpers.
//
// Rules every shader keeps (GLSL 4.60, SPIR-V 1.5, Vulkan 1.2): what one driver forgives,
// another does not.
// - No signed % or / with an operand that may be negative: the result is undefined (lavapipe
//   returns C's remainder, NVIDIA does not). Reduce magnitudes in unsigned arithmetic.
// - No shift by the operand's bit width or more.
// - Float-to-integer conversions only of values known to be in range: texel coordinates are,
//   because the library bounds UVs by 2^24 and map sides by 2^32; counts are clamped first.
// - Every variable and shared element is written before it is read.
// - barrier() only where the whole workgroup gets there: in loops whose trip count is
//   workgroup-uniform, never under a per-invocation condition.
// - No subgroup size assumed (lavapipe 8, NVIDIA 32, AMD 64, Intel 8 to 32), and no reliance on
//   reconvergence beyond SPIR-V's rule: control flow uniform on entry to a selection or loop
//   reconverges at its merge block. Subgroup operations therefore run either at the top level
//   of main (after such constructs), or inside loops whose trip count is subgroup-uniform,
//   with a per-invocation predicate instead of divergent control flow. A ballot's find-LSB is
//   read only when the ballot is known to be non-empty.
// - A later dispatch sees an earlier one's writes only through a pipeline barrier recorded
//   between them (Commands::barrier); the host reads results after the fence, from memory the
//   last barrier made host-visible. Atomics go only to device-local memory.
#ifndef LIGHTSAMPLER_COMMON_GLSL
#define LIGHTSAMPLER_COMMON_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_atomic_float : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_shader_subgroup_extended_types_int64 : require

#include "shared.h"

// The paper's "No Subgroup Reduction" ablation (Figure 14), specialized by the host: false makes
// every invocation of the counting passes and of the unordered scan issue its own atomics
// instead of one per subgroup (or workgroup).
layout(constant_id = 0) const bool kSubgroupReduction = true;

// The triangle-texel overlap formula of the counting passes (lightsampler::Overlap: the closed
// form, polygon clipping or the paper's Eq. 6), specialized by the host (Figures 11 and 12).
layout(constant_id = 1) const uint kOverlap = kOverlapClosedForm;

layout(buffer_reference, std430, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Uints { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Uint64s { uint64_t v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Doubles { double v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Triangles { TexelTriangle v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Maps { DensityMap v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Samples { Sample v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Totals { FrameTotals t; };

// Element i of a uint64 array beyond 2^32 elements: index by address arithmetic.
Uint64s uint64_at(uint64_t base, uint64_t i) { return Uint64s(base + i * 8ul); }

// ---- the counts' inclusive CDF over processing indices (uint64[count]) ----

uint64_t cdf_at(uint64_t cdf, uint position) { return uint64_at(cdf, position).v[0]; }

// The first processing index in [lo, hi] whose inclusive CDF exceeds sample_index, given one
// does (hi where none before it does).
uint first_above(uint64_t cdf, uint64_t sample_index, uint lo, uint hi) {
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (cdf_at(cdf, mid) > sample_index) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

// The first processing index whose inclusive CDF exceeds sample_index: the triangle whose slots
// hold that sample.
uint processing_index(uint64_t cdf, uint count, uint64_t sample_index) {
  return first_above(cdf, sample_index, 0u, count - 1u);
}

// ---- texel lookup (core/density.h: address, cell_density, floor_to_int, point_density) ----

// Cell i of any sign, wrapped, clamped or mirrored into [0, n). Wrap and mirror reduce |i| in
// unsigned arithmetic: for i < 0, the cell -1 - k (k >= 0) wraps to n - 1 - (k mod n); mirror's
// period is 2n, where it is the cell 2n - 1 - (k mod 2n), and the period's second half reads the
// map backwards.
uint address(int64_t i, uint n, uint addressing) {
  if (i >= 0l && i < int64_t(n)) return uint(i);
  if (addressing == kAddressClamp) return i < 0l ? 0u : n - 1u;
  if (addressing == kAddressMirror) {
    uint64_t period = 2ul * uint64_t(n);
    uint64_t m = i >= 0l ? uint64_t(i) % period : period - 1ul - uint64_t(-(i + 1l)) % period;
    return uint(m < uint64_t(n) ? m : period - 1ul - m);
  }
  if (i >= 0l) return uint(uint64_t(i) % uint64_t(n));
  return n - 1u - uint(uint64_t(-(i + 1l)) % uint64_t(n));
}

float cell_density(DensityMap map, uint64_t texels, int64_t ix, int64_t iy) {
  uint index = map.offset + address(iy, map.height, map.addressing) * map.width +
               address(ix, map.width, map.addressing);
  return Floats(texels).v[index] * map.scale;
}

// x is a texel coordinate, |x| < 2^56 (see the rules above), so the conversion is defined.
int64_t floor_to_int(float x) {
  int64_t i = int64_t(x);  // truncates toward zero
  return float(i) > x ? i - 1l : i;
}

float point_density(DensityMap map, uint64_t texels, float x, float y) {
  return cell_density(map, texels, floor_to_int(x), floor_to_int(y));
}

// ---- random numbers (lightsampler/random.h) ----

uvec4 philox4x32(uvec4 c, uvec2 k) {
  const uint kM0 = 0xD2511F53u, kM1 = 0xCD9E8D57u, kW0 = 0x9E3779B9u, kW1 = 0xBB67AE85u;
  for (int round = 0; round < 10; ++round) {
    uint hi0, lo0, hi1, lo1;
    umulExtended(kM0, c.x, hi0, lo0);
    umulExtended(kM1, c.z, hi1, lo1);
    c = uvec4(hi1 ^ c.y ^ k.x, lo1, hi0 ^ c.w ^ k.y, lo0);
    k += uvec2(kW0, kW1);
  }
  return c;
}

// The candidate stream's counter (core::candidate_counter): (T, j, s) in 128 bits, collision-free for s < 2^56 and j < 2^40.
uvec4 candidate_counter(uint triangle, uint64_t segment, uint64_t candidate) {
  return uvec4(triangle, uint(candidate), uint(segment),
               uint(segment >> 32) ^ (uint(candidate >> 32) << 24));
}

float uniform_float(uint bits) { return float(bits >> 8) * (1.0 / 16777216.0); }
double uniform_double(uint bits) { return double(bits) * (1.0lf / 4294967296.0lf); }
// Uniform double in [0, 1) with 53 random bits (core/frame_policy.h).
double uniform53(uvec4 r) {
  return double(((uint64_t(r.x) << 32) | uint64_t(r.y)) >> 11) * (1.0lf / 9007199254740992.0lf);
}

// ---- Heitz's low-distortion map (lightsampler/triangle_map.h) ----

vec2 triangle_map(float u0, float u1) {
  float t0, t1;
  if (u0 < u1) {
    t0 = 0.5 * u0;
    t1 = u1 - t0;
  } else {
    t1 = 0.5 * u1;
    t0 = u0 - t1;
  }
  return vec2(t1, 1.0 - (u0 < u1 ? u1 : u0));
}

// The texel-space point at barycentrics (b1, b2). precise: no fused multiply-add, so the texel
// it falls in is the one the CPU backend reads, bit for bit.
vec2 texel_space_point(TexelTriangle t, vec2 b) {
  precise float x = t.origin_x + b.x * t.edge1_x + b.y * t.edge2_x;
  precise float y = t.origin_y + b.x * t.edge1_y + b.y * t.edge2_y;
  return vec2(x, y);
}

// Density at barycentrics (b1, b2) of a triangle, as the realization pass reads it.
float texel_triangle_density(TexelTriangle t, Maps maps, uint64_t texels, vec2 b) {
  if (t.map == kNoMap) return 0.0;
  vec2 p = texel_space_point(t, b);
  return point_density(maps.v[t.map], texels, p.x, p.y);
}

bool uv_degenerate(TexelTriangle t) {
  return t.edge1_x == 0.0 && t.edge1_y == 0.0 && t.edge2_x == 0.0 && t.edge2_y == 0.0;
}

// Non-negative floats order as their bits: atomicMax on uint is a float max.
void atomic_max_float(Uints values, uint i, float value) {
  atomicMax(values.v[i], floatBitsToUint(value));
}

#endif
