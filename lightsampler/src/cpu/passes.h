#pragma once
// The CPU backend's passes (paper, Section 3). Each is a free function over plain arrays so that
// tests can drive it directly; CpuSampler strings them together and times them. The counting
// pass is the core's (core/counting.h).

#include <cstdint>
#include <span>
#include <vector>

#include "core/candidate_stream.h"
#include "core/density.h"
#include "core/geometry.h"
#include "lightsampler/buffer.h"
#include "lightsampler/random.h"
#include "lightsampler/sample.h"
#include "lightsampler/sampler.h"

namespace lightsampler::cpu {

/// Stochastic rounding of scale * N-bar_T (Algorithm 2, lines 12-14): floor, plus one with
/// probability equal to the fraction, from the rounding stream keyed by triangle. Returns N.
std::uint64_t round_counts(std::span<const double> expected_counts, double scale, PhiloxKey key,
                           Buffer<std::uint64_t>& counts);

/// Unordered cumulative sum (Algorithm 3): inclusive CDF in processing order and the inverse
/// permutation. Each task reserves a block of up to `block` consecutive elements with one packed
/// atomic add (the CPU form of the subgroup reduction of Section 5); block = 1 is Algorithm 3
/// verbatim. Requires unordered_scan_fits(counts.size(), total).
void unordered_scan(std::span<const std::uint64_t> counts, std::size_t block, Buffer<std::uint64_t>& cdf,
                    Buffer<std::uint32_t>& inverse_permutation);

/// Ordered inclusive prefix sum; the inverse permutation is the identity.
void ordered_scan(std::span<const std::uint64_t> counts, Buffer<std::uint64_t>& cdf,
                  Buffer<std::uint32_t>& inverse_permutation);

struct RealizationResult {
  std::uint64_t candidates = 0;
  std::uint64_t exhausted = 0;
  std::uint64_t exact = 0;  ///< TRS: slots drawn from texel pieces after rejection stopped
};

/// Philox keys of TRS's realization: the candidate stream's, and the exact draws'.
struct RealizationKeys {
  PhiloxKey candidates;
  PhiloxKey exact;
};

/// Realization pass (Algorithm 4): the N_T slots of triangle sigma^-1[p] start at cdf[p - 1];
/// candidates from Heitz's map, accepted against D_T^max, fill them through the candidate stream
/// (core/candidate_stream.h), keyed by triangle, so a triangle's samples do not depend on
/// scheduling or scan order. A walk that the limit stops fills the rest of its segment with exact
/// draws (core/piece_draw.h): slot k of the triangle from counter (T, k, attempt), at most
/// max_tries attempts each.
RealizationResult realize(std::span<const core::TexelTriangle> triangles,
                          std::span<const core::DensityMap> maps, std::span<const float> max_density,
                          std::span<const std::uint64_t> cdf,
                          std::span<const std::uint32_t> inverse_permutation, RealizationKeys keys,
                          core::TrsTries tries, Buffer<Sample>& samples);

/// Plain rejection sampling (Algorithm 1): triangles by area, uniform points, accepted against
/// the global max density, through the candidate stream over the whole output. `area_cdf` is
/// the inclusive CDF of triangle areas, `area_guide` its cutpoints (core/area_pick.h).
RealizationResult rejection_sample(std::span<const core::TexelTriangle> triangles,
                                   std::span<const core::DensityMap> maps, std::span<const double> area_cdf,
                                   std::span<const std::uint32_t> area_guide, float global_max_density, std::uint64_t sample_count,
                                   PhiloxKey key, std::uint32_t max_tries, Buffer<Sample>& samples);

/// Inclusive CDF of world areas, its cutpoints, and the max density of every map a triangle
/// uses: what plain rejection sampling needs. Returns the max density.
float rejection_distribution(std::span<const core::TriangleRecord> triangles,
                             std::span<const core::DensityMap> maps, Buffer<double>& area_cdf,
                             std::vector<std::uint32_t>& area_guide);

/// Naive triangle stratification's counting (paper, Section 3.2): each triangle walks the
/// texels it overlaps, clips each by polygon clipping (core/texel_pieces.h) and sums density
/// times overlap area into N-bar_T, and the largest density met into D_T^max. Returns N-bar.
double naive_count(std::span<const core::TriangleRecord> records,
                   std::span<const core::TexelTriangle> triangles,
                   std::span<const core::DensityMap> maps, Buffer<double>& expected_counts,
                   Buffer<float>& max_density);

/// Naive triangle stratification's realization: the N_T slots of triangle sigma^-1[p] start at
/// cdf[p - 1]; each draws a texel piece of its triangle in proportion to density times area,
/// then a uniform point in the piece. No rejection: a point is drawn again only when rounding
/// puts it in another texel than its piece's (counted in candidates, bounded by max_tries).
RealizationResult naive_realize(std::span<const core::TexelTriangle> triangles,
                                std::span<const core::DensityMap> maps,
                                std::span<const std::uint64_t> cdf,
                                std::span<const std::uint32_t> inverse_permutation, PhiloxKey key,
                                std::uint32_t max_tries, Buffer<Sample>& samples);

/// The time of `runs` passes writing `count` samples to host memory with the backend's threads
/// (the floor under realization), in milliseconds. Each pass writes every sample anew.
std::vector<double> sample_write_ms(const CpuOptions& options, std::uint64_t count, int runs);

}  // namespace lightsampler::cpu
