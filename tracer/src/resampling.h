#pragma once
// `ris`, in one place: resampled importance sampling (Talbot et al. 2005) of next-event
// connections over any strategy's light samples. The strategy `ris` is its source under another
// name, with its number of candidates (`restir` too, reused by reuse.h); resample() draws that many candidates for
// a shading point, weighs each by the luminance of what it would bring unshadowed (target over
// source density), keeps one in proportion to its weight, and gives the factor its estimate is
// scaled by, the weights' mean over its own weight, which makes it unbiased for any number of
// candidates, the set drawn afresh per query. With one candidate it is the strategy's own sample.

#include <algorithm>
#include <array>
#include <memory>
#include <optional>

#include <lightsampler/random.h>

#include "luminance.h"
#include "tracer/light_strategy.h"
#include "tracer/path_random.h"

namespace tracer {

template <class Connection>
struct Resampled {
  Connection kept;
  float scale;  ///< the weights' mean over the kept one's
};

/// strategy.candidates() light samples for `at`, each made a Connection by `connect` (none where
/// it brings nothing; its `unshadowed` is f Li over the sample's solid-angle density), one kept.
template <class Connection, class Connect>
std::optional<Resampled<Connection>> resample(const LightStrategy& strategy, PathRandom& random,
                                              const ShadingPoint& at, Connect&& connect) {
  const unsigned candidates = strategy.candidates();
  std::optional<Connection> kept;
  float kept_weight = 0.0f, weight_sum = 0.0f;
  // In batches: a batch's candidates are fetched from memory together, then weighed.
  constexpr unsigned kBatch = 16;
  std::array<LightRandom, kBatch> words;
  for (unsigned first = 0; first < candidates; first += kBatch) {
    const unsigned batch = std::min(kBatch, candidates - first);
    for (unsigned i = 0; i < batch; ++i) {
      const auto low = random.words(), high = random.words();
      std::copy(low.begin(), low.end(), words[i].begin());
      std::copy(high.begin(), high.end(), words[i].begin() + 4);
      strategy.prefetch(words[i]);
    }
    for (unsigned i = 0; i < batch; ++i) {
      const std::optional<LightLiSample> s = strategy.sample(words[i], at);
      if (!s) continue;
      std::optional<Connection> c = connect(*s);
      if (!c) continue;
      const float weight = luminance(c->unshadowed);
      if (!(weight > 0.0f)) continue;
      weight_sum += weight;
      // A one-slot reservoir: each candidate replaces the kept one with probability weight / sum
      // (the first always: it needs no coin).
      if (!kept || lightsampler::uniform_float(random.words()[0]) * weight_sum < weight) {
        kept = std::move(c);
        kept_weight = weight;
      }
    }
  }
  if (!kept) return std::nullopt;
  // One candidate: weight_sum / kept_weight is one, the plain estimate.
  const float scale = candidates == 1 ? 1.0f : weight_sum / (float(candidates) * kept_weight);
  return Resampled<Connection>{std::move(*kept), scale};
}

}  // namespace tracer
