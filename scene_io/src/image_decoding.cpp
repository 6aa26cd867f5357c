#include "image_decoding.h"

#include "scene_io/file_error.h"
#include "scene_io/input_file.h"

namespace trs {

image_codec::Decoder open_image(const std::filesystem::path& file) {
  check_input_file(file);
  try {
    return image_codec::Decoder(file);
  } catch (const image_codec::CodecError& error) {
    throw FileError(file, std::string("cannot read image: ") + error.what());
  }
}

image_codec::Decoder open_image(std::span<const unsigned char> bytes, const std::string& format,
                                const std::filesystem::path& file, const std::string& context) {
  try {
    return image_codec::Decoder(bytes, format);
  } catch (const image_codec::FileOnlyFormat& format_name) {
    throw FileError(file, context + format_name.what() +
                              " images can only be read from files, not embedded");
  } catch (const image_codec::CodecError& error) {
    throw FileError(file, context + "cannot decode image: " + error.what());
  }
}

DecodedImage decode(image_codec::Decoder& decoder, const std::filesystem::path& file,
                    const std::string& context, bool alpha) {
  auto fail = [&](const std::string& problem) { throw FileError(file, context + problem); };
  const image_codec::Header& header = decoder.header();
  if (header.deep) fail("deep images are not supported");
  if (header.depth != 1) fail("volume images (" + std::to_string(header.depth) + " slices) are not supported");
  if (header.width <= 0 || header.height <= 0 || header.channels <= 0) fail("image has no pixels");
  check_image_size(file, header.width, header.height);

  DecodedImage image;
  image.width = static_cast<std::uint32_t>(header.width);
  image.height = static_cast<std::uint32_t>(header.height);
  // Only the channels that make the colour or the density are read, and alpha where it is
  // asked for: an RGBA image would otherwise spend a quarter of its memory on alpha.
  image.channels = header.channels >= 3 ? 3 : 1;
  if (alpha && header.alpha) ++image.channels;
  image.integer = header.integer;
  image.declared_linear = header.declared_linear;
  try {
    image.pixels = decoder.read(image.channels);
  } catch (const image_codec::CodecError& error) {
    fail(std::string("cannot read pixels (truncated or corrupt file?): ") + error.what());
  }
  return image;
}

DecodedImage decode_image(const std::filesystem::path& file) {
  image_codec::Decoder decoder = open_image(file);
  return decode(decoder, file, "");
}

}  // namespace trs
