#pragma once
// Random numbers of one path: Philox4x32-10 keyed by the render's seed, counter (pixel, frame,
// draw), so that an image does not depend on the thread count or the order of the work.

#include <array>
#include <cstdint>

#include <lightsampler/random.h>

namespace tracer {

class PathRandom {
 public:
  PathRandom(const lightsampler::PhiloxKey& key, std::uint32_t pixel, std::uint32_t frame)
      : key_(key), pixel_(pixel), frame_(frame) {}

  /// Four fresh uniform 32-bit words.
  std::array<std::uint32_t, 4> words() {
    return lightsampler::philox4x32({pixel_, frame_, draw_++, 0u}, key_);
  }

  /// Three uniform floats in [0, 1).
  std::array<float, 3> floats() {
    const auto w = words();
    return {lightsampler::uniform_float(w[0]), lightsampler::uniform_float(w[1]),
            lightsampler::uniform_float(w[2])};
  }

 private:
  lightsampler::PhiloxKey key_;
  std::uint32_t pixel_;
  std::uint32_t frame_;
  std::uint32_t draw_ = 0;
};

/// The path-tracing stream of a render seed, apart from every stream the light sampler uses.
inline lightsampler::PhiloxKey path_key(std::uint64_t seed) {
  const std::uint64_t k = lightsampler::mix64(lightsampler::mix64(seed) ^ 0x7472616365722121ull);
  return {std::uint32_t(k), std::uint32_t(k >> 32)};
}

}  // namespace tracer
