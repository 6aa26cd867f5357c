#pragma once
// Reading a texture at a UV: bilinear (or nearest, when the texture asks) with its wrap modes.

#include <glm/glm.hpp>

#include "tracer/scene.h"

namespace tracer {

glm::vec3 lookup(const Texture& texture, glm::vec2 uv);

}  // namespace tracer
