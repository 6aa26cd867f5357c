#pragma once
// Emissive textures that play a sequence of images: a glTF image with "extras": {"frames":
// "screen.%04d.png"}, a printf pattern relative to the glTF file whose frame f is the image of
// animation frame f. Its "uri" stays an ordinary image (the poster), which other glTF viewers
// show.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "tracer/scene.h"

namespace tracer {

/// The sequence of `pattern` next to `document`: every frame that has a file, which must run
/// without a gap and have the poster's size. Throws trs::FileError naming the document (a bad
/// pattern, no frame at all, a missing frame) or the frame's file (another size, not an image);
/// `what` names the image in messages.
ImageSequence read_image_sequence(const std::filesystem::path& document, const std::string& pattern,
                                  std::uint32_t width, std::uint32_t height, const std::string& what);

/// The linear texels of the image that stands at animation frame `frame` in the texture's
/// sequence. Throws trs::FileError naming the frame's file.
std::vector<glm::vec3> read_sequence_frame(const Texture& texture, std::int64_t frame);

}  // namespace tracer
