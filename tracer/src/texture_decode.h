#pragma once
// Decoded image pixels to a texture's linear texels: what a glTF texture and every image of a
// texture's sequence go through alike.

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene_io/image_output.h"

namespace tracer {

/// The pixels as linear RGB: decoded from sRGB where they hold `colour` in integers, as they
/// are otherwise. Throws trs::FileError naming `file` (`prefix` before the problem) at a texel
/// that is not finite.
std::vector<glm::vec3> linear_texels(trs::Image pixels, bool colour, const std::filesystem::path& file,
                                     const std::string& prefix);

}  // namespace tracer
