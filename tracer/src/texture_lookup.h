#pragma once
// Reading a texture at a UV: bilinear (or nearest, when the texture asks) with its wrap modes.

#include <array>

#include <glm/glm.hpp>

#include "tracer/scene.h"

namespace tracer {

/// A surface point's coordinates in every UV set.
using SurfaceUvs = std::array<glm::vec2, kUvSets>;

/// Where a texture reference reads at a surface point: its UV set, transformed.
inline glm::vec2 texture_uv(const TextureRef& ref, const SurfaceUvs& uv) { return ref.transform(uv[ref.uv_set]); }

/// The texture's colour at texture coordinates `uv` (texture_uv).
glm::vec3 lookup(const Texture& texture, glm::vec2 uv);
/// The texture's alpha at `uv`, filtered as its colour: 1 where it has none.
float lookup_alpha(const Texture& texture, glm::vec2 uv);

}  // namespace tracer
