#include "texture_lookup.h"

#include <cmath>
#include <cstdint>

namespace tracer {
namespace {

/// Texel index along one axis for lattice cell i of a texture n texels wide.
std::uint32_t wrap(std::int64_t i, std::uint32_t n, Wrap mode) {
  const auto size = std::int64_t(n);
  switch (mode) {
    case Wrap::clamp: return std::uint32_t(i < 0 ? 0 : (i >= size ? size - 1 : i));
    case Wrap::mirrored_repeat: {
      const std::int64_t period = ((i % (2 * size)) + 2 * size) % (2 * size);
      return std::uint32_t(period < size ? period : 2 * size - 1 - period);
    }
    case Wrap::repeat: break;
  }
  return std::uint32_t(((i % size) + size) % size);
}

std::size_t texel_index(const Texture& t, std::int64_t x, std::int64_t y) {
  return std::size_t(wrap(y, t.height, t.wrap_t)) * t.width + wrap(x, t.width, t.wrap_s);
}

/// `texels` (the texture's colours or alphas) read at `uv` as the texture's filter asks.
template <class Texels>
auto filtered(const Texture& texture, const Texels& texels, glm::vec2 uv) {
  const float x = uv.x * float(texture.width);
  const float y = uv.y * float(texture.height);
  if (texture.nearest) return texels[texel_index(texture, std::int64_t(std::floor(x)), std::int64_t(std::floor(y)))];
  // Texel centres sit at half-integers.
  const float fx = x - 0.5f, fy = y - 0.5f;
  const float x0 = std::floor(fx), y0 = std::floor(fy);
  const float tx = fx - x0, ty = fy - y0;
  const auto ix = std::int64_t(x0), iy = std::int64_t(y0);
  auto at = [&](std::int64_t i, std::int64_t j) { return texels[texel_index(texture, i, j)]; };
  return (1 - ty) * ((1 - tx) * at(ix, iy) + tx * at(ix + 1, iy)) +
         ty * ((1 - tx) * at(ix, iy + 1) + tx * at(ix + 1, iy + 1));
}

}  // namespace

glm::vec3 lookup(const Texture& texture, glm::vec2 uv) { return filtered(texture, texture.texels, uv); }

float lookup_alpha(const Texture& texture, glm::vec2 uv) {
  return texture.alpha.empty() ? 1.0f : filtered(texture, texture.alpha, uv);
}

}  // namespace tracer
