#include "cpu/candidates.h"

// GCC notes that vectors wider than the baseline's registers are passed differently under
// AVX-512; here none crosses a call (the helpers are inlined), so the note does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace lightsampler::cpu {

namespace {

// GCC vector extensions: kLanes lanes, one 32-bit Philox word per 64-bit lane so that the
// 32x32 -> 64-bit products are plain vector multiplies.
using U64 = std::uint64_t __attribute__((vector_size(8 * kLanes)));
using U32 = std::uint32_t __attribute__((vector_size(4 * kLanes)));
using F32 = float __attribute__((vector_size(4 * kLanes)));
using F64 = double __attribute__((vector_size(8 * kLanes)));

}  // namespace

// One build for every x86-64, the widest vectors the processor has chosen at load time.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define LIGHTSAMPLER_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define LIGHTSAMPLER_VECTOR_CLONES
#endif

LIGHTSAMPLER_VECTOR_CLONES
void draw_candidates(std::uint32_t triangle, std::uint64_t segment, std::uint64_t first, PhiloxKey key,
                     CandidateBatch& out) {
  // core::candidate_counter, per lane.
  U64 j;
  for (int l = 0; l < kLanes; ++l) j[l] = first + std::uint64_t(l);
  const U64 low = U64{} + 0xffffffffu;
  U64 c0 = U64{} + triangle, c1 = j & low, c2 = U64{} + (segment & 0xffffffffu);
  U64 c3 = (((j >> 32) << 24) ^ (segment >> 32)) & low;
  std::uint32_t k0 = key[0], k1 = key[1];
#pragma GCC unroll 10
  for (int round = 0; round < 10; ++round) {
    const U64 p0 = c0 * 0xD2511F53u, p1 = c2 * 0xCD9E8D57u;
    c0 = (p1 >> 32) ^ c1 ^ k0;
    c1 = p1 & low;
    c2 = (p0 >> 32) ^ c3 ^ k1;
    c3 = p0 & low;
    k0 += 0x9E3779B9u;
    k1 += 0xBB67AE85u;
  }
  // lightsampler::uniform_float per lane.
  auto uniform_float = [](U64 bits) {
    return __builtin_convertvector(__builtin_convertvector(bits >> 8, U32), F32) * 0x1p-24f;
  };
  // triangle_map(u0, u1): b1 = t1, b2 = 1 - max(u0, u1).
  const F32 u0 = uniform_float(c0), u1 = uniform_float(c1);
  const auto below = u0 < u1;
  const F32 b1 = below ? u1 - 0.5f * u0 : 0.5f * u1;
  const F32 b2 = 1.0f - (below ? u1 : u0);
  const F32 accept = uniform_float(c2);
  const F64 pick = __builtin_convertvector(c3, F64) * 0x1p-32;
  for (int l = 0; l < kLanes; ++l) {
    out.b1[l] = b1[l];
    out.b2[l] = b2[l];
    out.accept[l] = accept[l];
    out.pick[l] = pick[l];
  }
}

LIGHTSAMPLER_VECTOR_CLONES
std::uint32_t accepted_on_triangle(const core::TexelTriangle& t, const core::DensityMap& map, float bound,
                                   const CandidateBatch& batch) {
  // Plain loops over the lanes, which the compiler turns into vector code.
  alignas(64) float x[kLanes], y[kLanes], density[kLanes];
  int in_range = 0;
  // core::floor_to_int runs in 32-bit lanes where every point lies well inside their range
  // (UVs go to 2^24, so texel coordinates can leave it); otherwise lane by lane in 64 bits.
  constexpr float kRange = 0x1p30f;
  for (int l = 0; l < kLanes; ++l) {
    // core::texel_space_point, the same operations in the same order (no contraction).
    x[l] = t.origin[0] + batch.b1[l] * t.edge1[0] + batch.b2[l] * t.edge2[0];
    y[l] = t.origin[1] + batch.b1[l] * t.edge1[1] + batch.b2[l] * t.edge2[1];
    in_range += int(x[l] > -kRange) & int(x[l] < kRange) & int(y[l] > -kRange) & int(y[l] < kRange);
  }
  int inside = 0;
  alignas(64) std::uint32_t index[kLanes];
  if (in_range == kLanes)
    for (int l = 0; l < kLanes; ++l) {
      const std::int32_t tx = std::int32_t(x[l]), ty = std::int32_t(y[l]);  // truncated
      const auto ix = std::uint32_t(tx - int(float(tx) > x[l])), iy = std::uint32_t(ty - int(float(ty) > y[l]));
      inside += int(ix < map.width) & int(iy < map.height);
      index[l] = iy * map.width + ix;  // maps have at most 2^28 texels
    }
  if (inside == kLanes)
    for (int l = 0; l < kLanes; ++l) density[l] = map.texels[index[l]];
  else  // some lane outside the map or the 32-bit range: the addressing of core::cell_value
    for (int l = 0; l < kLanes; ++l) density[l] = core::cell_value(map, core::floor_to_int(x[l]), core::floor_to_int(y[l]));
  std::uint32_t accepted = 0;
  for (int l = 0; l < kLanes; ++l) accepted |= std::uint32_t(batch.accept[l] * bound < density[l] * map.scale) << l;
  return accepted;
}

}  // namespace lightsampler::cpu
