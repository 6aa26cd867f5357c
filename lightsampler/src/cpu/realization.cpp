#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cpu/passes.h"
#include "lightsampler/triangle_map.h"

namespace lightsampler::cpu {

namespace {

// Samples per task: large enough that the binary search that starts a task is amortised.
constexpr std::size_t kSamplesPerTask = 1 << 14;
// Samples whose first candidates are drawn together: independent work that the processor
// overlaps, instead of one long dependent chain (RNG, map, lookup, test) per sample.
constexpr int kBatch = 16;

struct Candidate {
  Barycentrics b;
  bool accepted;
};

Candidate draw(const core::TexelTriangle& t, const core::DensityMap& map, float bound, std::uint32_t tri,
               std::uint64_t rank, std::uint32_t attempt, PhiloxKey key) {
  const PhiloxCounter u =
      philox4x32({tri, std::uint32_t(rank), std::uint32_t(rank >> 32), attempt}, key);
  const Barycentrics b = triangle_map(uniform_float(u[0]), uniform_float(u[1]));
  const auto [x, y] = core::texel_space_point(t, b.b1, b.b2);
  const float d = core::point_density(map, x, y);
  return {b, uniform_float(u[2]) * bound < d};
}

}  // namespace

RealizationResult realize(std::span<const core::TexelTriangle> triangles,
                          std::span<const core::DensityMap> maps, std::span<const float> max_density,
                          std::span<const std::uint64_t> cdf,
                          std::span<const std::uint32_t> inverse_permutation, PhiloxKey key,
                          std::uint32_t max_tries, Buffer<Sample>& samples) {
  const std::uint64_t n = cdf.empty() ? 0 : cdf.back();
  samples.resize(n);
  std::atomic<std::uint64_t> candidates{0}, exhausted{0};
  tbb::parallel_for(
      tbb::blocked_range<std::uint64_t>(0, n, kSamplesPerTask),
      [&](const tbb::blocked_range<std::uint64_t>& r) {
        // Samples are consecutive, so after one binary search the triangles are walked in order.
        std::size_t p = std::size_t(std::upper_bound(cdf.begin(), cdf.end(), r.begin()) - cdf.begin());
        std::uint64_t begin = p == 0 ? 0 : cdf[p - 1];
        std::uint64_t tries = 0, gave_up = 0;
        std::uint32_t tri[kBatch];
        std::uint64_t rank[kBatch];
        Candidate first[kBatch];
        for (std::uint64_t i0 = r.begin(); i0 < r.end(); i0 += kBatch) {
          const int lanes = int(std::min<std::uint64_t>(kBatch, r.end() - i0));
          for (int k = 0; k < lanes; ++k) {
            while (i0 + k >= cdf[p]) begin = cdf[p++];
            tri[k] = inverse_permutation[p];
            rank[k] = i0 + k - begin;
          }
          for (int k = 0; k < lanes; ++k) {
            const core::TexelTriangle& t = triangles[tri[k]];
            first[k] = draw(t, maps[t.map], max_density[tri[k]], tri[k], rank[k], 0, key);
          }
          for (int k = 0; k < lanes; ++k) {
            const core::TexelTriangle& t = triangles[tri[k]];
            Candidate c = first[k];
            std::uint32_t attempt = 1;
            for (; !c.accepted && attempt < max_tries; ++attempt)
              c = draw(t, maps[t.map], max_density[tri[k]], tri[k], rank[k], attempt, key);
            samples[i0 + k] = {tri[k], c.b.b1, c.b.b2};
            gave_up += c.accepted ? 0 : 1;
            tries += attempt;
          }
        }
        candidates.fetch_add(tries, std::memory_order_relaxed);
        exhausted.fetch_add(gave_up, std::memory_order_relaxed);
      });
  return {candidates.load(), exhausted.load()};
}

}  // namespace lightsampler::cpu
