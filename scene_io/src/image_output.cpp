#include "scene_io/image_output.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "image_codec.h"
#include "image_decoding.h"
#include "scene_io/atomic_file.h"
#include "scene_io/file_error.h"

namespace trs {
namespace {

void check_size(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) throw FileError(file, "cannot write an image without pixels");
}

/// The codec encodes into memory and AtomicFile writes the bytes: the destination appears
/// complete or not at all whatever the format's writer does on failure.
void write_atomically(const std::filesystem::path& file,
                      const std::function<std::vector<unsigned char>()>& encode) {
  AtomicFile output(file);  // first, so that an unwritable destination fails before encoding
  std::vector<unsigned char> bytes;
  try {
    bytes = encode();
  } catch (const image_codec::CodecError& error) {
    throw FileError(file, std::string("cannot encode the image: ") + error.what());
  }
  output.write(bytes.data(), bytes.size());
  output.commit();
}

/// R, G, B per pixel, a grey image's one channel repeated; alpha apart.
Image to_rgb(DecodedImage decoded) {
  Image image;
  image.width = decoded.width;
  image.height = decoded.height;
  image.integer = decoded.integer;
  const std::size_t pixels = std::size_t(decoded.width) * decoded.height;
  const auto colours = std::size_t(decoded.channels >= 3 ? 3 : 1);
  if (decoded.channels == 2 || decoded.channels == 4) {  // alpha last: take it out
    const std::size_t stride = colours + 1;
    image.alpha.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      image.alpha[i] = decoded.pixels[stride * i + colours];
      std::copy_n(&decoded.pixels[stride * i], colours, &decoded.pixels[colours * i]);
    }
    decoded.pixels.resize(colours * pixels);
  }
  image.rgb = std::move(decoded.pixels);
  if (colours == 1) {  // spread in place, from the back
    image.rgb.resize(3 * pixels);
    for (std::size_t i = pixels; i-- > 0;) std::fill_n(&image.rgb[3 * i], 3, image.rgb[i]);
  }
  return image;
}

}  // namespace

void write_exr(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               const float* rgb) {
  check_size(file, width, height);
  write_atomically(file, [&] { return image_codec::encode_exr(width, height, rgb); });
}

std::vector<unsigned char> preview_rgb8(const float* rgb, std::size_t count, float exposure,
                                        const DisplayEncoder& display) {
  const float scale = std::exp2(exposure);
  std::vector<float> encoded(count);
  std::transform(rgb, rgb + count, encoded.begin(), [&](float value) { return value * scale; });
  display.encode(encoded);
  std::vector<unsigned char> bytes(count);
  std::transform(encoded.begin(), encoded.end(), bytes.begin(), [](float value) {
    const float clamped = value > 0.0f ? std::min(value, 1.0f) : 0.0f;  // NaN fails `> 0`
    return static_cast<unsigned char>(std::lround(clamped * 255.0f));
  });
  return bytes;
}

void write_png_preview(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
                       const float* rgb, float exposure, const DisplayEncoder& display) {
  check_size(file, width, height);
  write_png(file, width, height, preview_rgb8(rgb, 3 * std::size_t(width) * height, exposure, display).data());
}

void write_png(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               const unsigned char* rgb) {
  check_size(file, width, height);
  write_atomically(file, [&] { return image_codec::encode_png(width, height, rgb); });
}

Image read_exr(const std::filesystem::path& file) {
  image_codec::Decoder decoder = open_image(file);
  const std::string& format = decoder.header().format;
  if (format != "openexr") throw FileError(file, "is a " + format + " image, not OpenEXR");
  return to_rgb(decode(decoder, file, ""));
}

Image read_image(const std::filesystem::path& file, Alpha alpha) {
  image_codec::Decoder decoder = open_image(file);
  return to_rgb(decode(decoder, file, "", alpha == Alpha::keep));
}

std::pair<std::uint32_t, std::uint32_t> image_size(const std::filesystem::path& file) {
  const image_codec::Decoder decoder = open_image(file);
  return {std::uint32_t(decoder.header().width), std::uint32_t(decoder.header().height)};
}

Image read_image(std::span<const unsigned char> bytes, const std::string& format,
                 const std::filesystem::path& file, const std::string& what, Alpha alpha) {
  const std::string context = what + ": ";
  image_codec::Decoder decoder = open_image(bytes, format, file, context);
  return to_rgb(decode(decoder, file, context, alpha == Alpha::keep));
}

}  // namespace trs
