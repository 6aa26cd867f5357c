#pragma once
// Image decoding for scene_io's readers (colour images, density maps), over either codec: the
// input checks, the header checks, which channels are read, and every message naming the file.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "image_codec.h"

namespace trs {

/// An image's first subimage: its first channel (grey, or grey and alpha), or its first three
/// (R, G, B, dropping alpha and any others).
struct DecodedImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int channels = 0;           ///< 1 or 3; 2 or 4 with alpha last (decode's `alpha`)
  std::vector<float> pixels;  ///< `channels` per pixel, row-major, row 0 = the image's top row
  bool integer = false;          ///< as image_codec::Header
  bool declared_linear = false;  ///< as image_codec::Header
};

/// Opens an image file. Throws FileError naming `file`: missing, unreadable, not an image.
image_codec::Decoder open_image(const std::filesystem::path& file);

/// Opens an image file's bytes embedded in `file`; `format` is an extension ("png") and
/// `context` ("image 2: ") prefixes problems. Throws FileError naming `file`.
image_codec::Decoder open_image(std::span<const unsigned char> bytes, const std::string& format,
                                const std::filesystem::path& file, const std::string& context);

/// Checks the opened image's header and decodes its pixels: grey or RGB, and alpha after them
/// where `alpha` is asked for and the image has it. Throws FileError naming `file`: deep data,
/// no pixels, too many texels, truncated or corrupt pixel data.
DecodedImage decode(image_codec::Decoder& decoder, const std::filesystem::path& file,
                    const std::string& context, bool alpha = false);

/// open_image, then decode.
DecodedImage decode_image(const std::filesystem::path& file);

}  // namespace trs
