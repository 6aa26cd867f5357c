#pragma once
// Luminance of a glm colour, by the project's one definition (scene_io/color.h).

#include <glm/glm.hpp>

#include "scene_io/color.h"

namespace tracer {

inline float luminance(const glm::vec3& c) { return trs::luminance(c.r, c.g, c.b); }

}  // namespace tracer
