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
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
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

}  // namespace lightsampler::cpu
