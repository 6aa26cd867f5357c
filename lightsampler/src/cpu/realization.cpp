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

}  // namespace

RealizationResult realize(std::span<const TexelTriangle> triangles,
                          std::span<const DensityMap> maps, std::span<const float> max_density,
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
        for (std::uint64_t i = r.begin(); i != r.end(); ++i) {
          while (i >= cdf[p]) begin = cdf[p++];
          const std::uint32_t tri = inverse_permutation[p];
          const std::uint64_t rank = i - begin;
          const TexelTriangle& t = triangles[tri];
          const DensityMap& map = maps[t.map];
          const float bound = max_density[tri];
          for (std::uint32_t attempt = 0;;) {
            const PhiloxCounter u = philox4x32(
                {tri, std::uint32_t(rank), std::uint32_t(rank >> 32), attempt}, key);
            const Barycentrics b = triangle_map(uniform_float(u[0]), uniform_float(u[1]));
            const float d = point_density(map, t.origin[0] + b.b1 * t.edge1[0] + b.b2 * t.edge2[0],
                                          t.origin[1] + b.b1 * t.edge1[1] + b.b2 * t.edge2[1]);
            ++attempt;
            const bool accepted = uniform_float(u[2]) * bound < d;
            if (accepted || attempt == max_tries) {
              samples[i] = {tri, b.b1, b.b2};
              gave_up += accepted ? 0 : 1;
              tries += attempt;
              break;
            }
          }
        }
        candidates.fetch_add(tries, std::memory_order_relaxed);
        exhausted.fetch_add(gave_up, std::memory_order_relaxed);
      });
  return {candidates.load(), exhausted.load()};
}

}  // namespace lightsampler::cpu
