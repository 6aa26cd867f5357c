#include "scene_io/density_io.h"

#include <OpenImageIO/imageio.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "scene_io/color.h"
#include "scene_io/file_error.h"
#include "scene_io/input_file.h"

namespace trs {
namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

/// Whether the metadata declares linear values (or values that are data, not colour).
bool declared_linear(const OIIO::ImageSpec& spec) {
  const std::string space = lower(spec.get_string_attribute("oiio:ColorSpace"));
  if (space == "linear" || space == "scene_linear" || space.rfind("lin_", 0) == 0 ||
      space == "acescg" || space == "aces2065-1" || space == "raw" || space == "data" ||
      space == "non-color") {
    return true;
  }
  return spec.get_float_attribute("oiio:Gamma", 0.0f) == 1.0f;
}

bool integer_format(OIIO::TypeDesc format) {
  using B = OIIO::TypeDesc::BASETYPE;
  const auto base = B(format.basetype);
  return base == B::UINT8 || base == B::INT8 || base == B::UINT16 || base == B::INT16;
}

bool decode_srgb(const OIIO::ImageSpec& spec, MapEncoding encoding) {
  switch (encoding) {
    case MapEncoding::srgb:
      return true;
    case MapEncoding::linear:
      return false;
    case MapEncoding::automatic:
      return integer_format(spec.format) && !declared_linear(spec);
  }
  return false;
}

std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  return line.empty() ? "unknown error" : line;
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
  check_input_file(file);
  auto input = OIIO::ImageInput::open(file.string());
  if (!input) throw FileError(file, "cannot read image: " + first_line(OIIO::geterror()));
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.deep) throw FileError(file, "deep images are not supported");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw FileError(file, "image has no pixels");
  }
  check_image_size(file, spec.width, spec.height);

  DensityMap map;
  map.file = file;
  map.width = static_cast<std::uint32_t>(spec.width);
  map.height = static_cast<std::uint32_t>(spec.height);
  map.srgb_decoded = decode_srgb(spec, encoding);
  // Only the channels that make the density are read: an RGBA map would spend a quarter of its
  // memory on alpha.
  const int channels = spec.nchannels >= 3 ? 3 : 1;
  const std::size_t texel_count = std::size_t(map.width) * map.height;
  std::vector<float> pixels(texel_count * channels);
  // Some readers (JPEG) fill a truncated image with grey, report success and only record the
  // error.
  const bool read = input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data());
  if (!read || input->has_error()) {
    throw FileError(
        file, "cannot read pixels (truncated or corrupt file?): " + first_line(input->geterror()));
  }
  input->close();

  if (map.srgb_decoded) srgb_to_linear(pixels);
  if (channels == 1) {
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
