#include "scene_io/density_io.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "image_decoding.h"
#include "scene_io/color.h"
#include "scene_io/file_error.h"

namespace trs {
namespace {

bool decode_srgb(const DecodedImage& image, MapEncoding encoding) {
  switch (encoding) {
    case MapEncoding::srgb:
      return true;
    case MapEncoding::linear:
      return false;
    case MapEncoding::automatic:
      return image.integer && !image.declared_linear;
  }
  return false;
}

/// Throws at the first texel that the library would reject, saying where it is.
void check_texels(const DensityMap& map) {
  for (std::size_t i = 0; i < map.texels.size(); ++i) {
    const float value = map.texels[i];
    if (std::isfinite(value) && value >= 0) continue;
    std::ostringstream problem;
    problem << "texel (x " << i % map.width << ", y " << i / map.width << " from the top) is ";
    if (std::isnan(value)) {
      problem << "NaN";
    } else {
      problem << value;
    }
    problem << "; densities must be finite and non-negative";
    throw FileError(map.file, problem.str());
  }
}

}  // namespace

lightsampler::DensityMapView DensityMap::view(lightsampler::Addressing addressing,
                                              float scale) const {
  return {
      .texels = texels, .width = width, .height = height, .addressing = addressing, .scale = scale};
}

DensityMap load_density_map(const std::filesystem::path& file, MapEncoding encoding) {
  DecodedImage image = decode_image(file);
  DensityMap map;
  map.file = file;
  map.width = image.width;
  map.height = image.height;
  map.srgb_decoded = decode_srgb(image, encoding);
  std::vector<float>& pixels = image.pixels;
  const std::size_t texel_count = std::size_t(map.width) * map.height;

  if (map.srgb_decoded) srgb_to_linear(pixels);
  if (image.channels == 1) {
    map.texels = std::move(pixels);
  } else {
    map.texels.resize(texel_count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, texel_count),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const float* p = &pixels[i * 3];
                          map.texels[i] = luminance(p[0], p[1], p[2]);
                        }
                      });
  }
  check_texels(map);
  return map;
}

}  // namespace trs
