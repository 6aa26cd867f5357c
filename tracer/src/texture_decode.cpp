#include "texture_decode.h"

#include <cmath>
#include <cstring>

#include "scene_io/color.h"
#include "scene_io/file_error.h"

namespace tracer {

std::vector<glm::vec3> linear_texels(trs::Image pixels, bool colour, const std::filesystem::path& file,
                                     const std::string& prefix) {
  if (colour && pixels.integer) trs::srgb_to_linear(pixels.rgb);
  for (std::size_t i = 0; i < pixels.rgb.size(); ++i) {
    if (std::isfinite(pixels.rgb[i])) continue;
    const std::size_t texel = i / 3;
    throw trs::FileError(file, prefix + "texel (x " + std::to_string(texel % pixels.width) + ", y " +
                                   std::to_string(texel / pixels.width) + " from the top) is not finite");
  }
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  std::vector<glm::vec3> texels(pixels.rgb.size() / 3);
  std::memcpy(texels.data(), pixels.rgb.data(), pixels.rgb.size() * sizeof(float));
  return texels;
}

}  // namespace tracer
