#include "scene_io/image_output.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "scene_io/atomic_file.h"
#include "scene_io/color.h"
#include "scene_io/file_error.h"
#include "scene_io/input_file.h"

namespace trs {
namespace {

std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  return line.empty() ? "unknown error" : line;
}

void check_size(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) throw FileError(file, "cannot write an image without pixels");
}

/// OpenImageIO encodes into memory and AtomicFile writes the bytes: the destination appears
/// complete or not at all whatever the format's writer does on failure.
void write_atomically(const std::filesystem::path& file, const char* format,
                      const OIIO::ImageSpec& spec, const void* pixels) {
  AtomicFile output(file);  // first, so that an unwritable destination fails before encoding
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  const auto encoder = OIIO::ImageOutput::create(format, &memory);
  if (!encoder) {
    throw FileError(file, std::string("no ") + format + " writer: " + first_line(OIIO::geterror()));
  }
  if (!encoder->open(file.string(), spec) || !encoder->write_image(spec.format, pixels) ||
      !encoder->close()) {
    throw FileError(file, "cannot encode the image: " + first_line(encoder->geterror()));
  }
  output.write(bytes.data(), bytes.size());
  output.commit();
}

/// The first subimage's R, G, B of an opened input; `context` prefixes problems.
Image read_rgb(OIIO::ImageInput* input, const std::filesystem::path& file,
               const std::string& context) {
  auto fail = [&](const std::string& problem) { throw FileError(file, context + problem); };
  if (!input) fail("cannot read image: " + first_line(OIIO::geterror()));
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.deep) fail("deep images are not supported");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) fail("image has no pixels");
  check_image_size(file, spec.width, spec.height);
  using Base = OIIO::TypeDesc::BASETYPE;
  const auto base = Base(spec.format.basetype);

  Image image;
  image.width = static_cast<std::uint32_t>(spec.width);
  image.height = static_cast<std::uint32_t>(spec.height);
  image.integer =
      base == Base::UINT8 || base == Base::INT8 || base == Base::UINT16 || base == Base::INT16;
  const std::size_t pixels = std::size_t(image.width) * image.height;
  const int channels = spec.nchannels >= 3 ? 3 : 1;  // grey, or grey and alpha: the grey
  image.rgb.resize(3 * pixels);
  // Some readers (JPEG) fill a truncated image with grey, report success and only record the
  // error.
  const bool read = input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, image.rgb.data());
  if (!read || input->has_error())
    fail("cannot read pixels (truncated or corrupt file?): " + first_line(input->geterror()));
  if (channels == 1) {  // spread in place, from the back
    for (std::size_t i = pixels; i-- > 0;) std::fill_n(&image.rgb[3 * i], 3, image.rgb[i]);
  }
  return image;
}

std::unique_ptr<OIIO::ImageInput> open_file(const std::filesystem::path& file) {
  check_input_file(file);
  return OIIO::ImageInput::open(file.string());
}

}  // namespace

void write_exr(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               const float* rgb) {
  check_size(file, width, height);
  OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  write_atomically(file, "openexr", spec, rgb);
}

void write_png_preview(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
                       const float* rgb, float exposure) {
  check_size(file, width, height);
  const std::size_t count = 3 * std::size_t(width) * height;
  const float scale = std::exp2(exposure);
  std::vector<float> display(count);
  std::transform(rgb, rgb + count, display.begin(), [&](float value) { return value * scale; });
  linear_to_srgb(display);
  std::vector<unsigned char> bytes(count);
  std::transform(display.begin(), display.end(), bytes.begin(), [](float value) {
    const float clamped = value > 0.0f ? std::min(value, 1.0f) : 0.0f;  // NaN fails `> 0`
    return static_cast<unsigned char>(std::lround(clamped * 255.0f));
  });
  write_png(file, width, height, bytes.data());
}

void write_png(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               const unsigned char* rgb) {
  check_size(file, width, height);
  OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  write_atomically(file, "png", spec, rgb);
}

Image read_exr(const std::filesystem::path& file) {
  const auto input = open_file(file);
  if (input && std::string(input->format_name()) != "openexr")
    throw FileError(file, std::string("is a ") + input->format_name() + " image, not OpenEXR");
  return read_rgb(input.get(), file, "");
}

Image read_image(const std::filesystem::path& file) {
  return read_rgb(open_file(file).get(), file, "");
}

Image read_image(std::span<const unsigned char> bytes, const std::string& format,
                 const std::filesystem::path& file, const std::string& what) {
  const std::string context = what + ": ";
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  // The extension picks the first reader to try; OpenImageIO tries the others after it.
  const auto input = OIIO::ImageInput::open("embedded." + format, nullptr, &memory);
  if (!input) {
    const std::string error = first_line(OIIO::geterror());
    const auto reader = OIIO::ImageInput::create(format);
    if (reader && !reader->supports("ioproxy")) {
      throw FileError(file, context + reader->format_name() +
                                " images can only be read from files, not embedded");
    }
    throw FileError(file, context + "cannot decode image: " + error);
  }
  return read_rgb(input.get(), file, context);
}

}  // namespace trs
