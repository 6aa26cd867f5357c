#pragma once
// The one interface between scene_io and the library that encodes and decodes image files. Each
// build compiles one implementation (CMake option TRS_OPENIMAGEIO):
// - image_codec_oiio.cpp: OpenImageIO, every format it reads, colour-space metadata honoured;
// - image_codec_builtin.cpp: stb_image (PNG, JPEG, BMP, TGA, HDR, binary PNM...) and OpenEXR,
//   no colour-space metadata read.
// Everything around the codec (checks, messages naming the file, colour decisions) is written
// once, in image_decoding.cpp and image_output.cpp. Decoding takes two steps, header then pixels,
// so that a header is checked before anything is allocated for its pixels.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace trs::image_codec {

/// A codec's failure in its library's words, kept to their first line: the callers' messages
/// are one line, and they name the file.
class CodecError : public std::runtime_error {
 public:
  explicit CodecError(const std::string& message)
      : std::runtime_error(first_line(message)) {}

 private:
  static std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    return line.empty() ? "unknown error" : line;
  }
};

/// Thrown for embedded bytes in a format that the codec reads only from files; what() is the
/// format's name.
class FileOnlyFormat : public CodecError {
 public:
  using CodecError::CodecError;
};

/// What an image's header says about its first subimage.
struct Header {
  std::string format;  ///< OpenImageIO's name for it: "openexr", "png", "jpeg", "targa"...
  int width = 0;
  int height = 0;
  int channels = 0;  ///< as stored (RGBA: 4)
  /// The last of 2 or 4 channels is alpha (grey and alpha, RGBA), in the order read() gives them.
  bool alpha = false;
  bool deep = false;
  int depth = 1;  ///< slices: more than 1 in a volume image
  bool integer = false;          ///< stored as 8- or 16-bit integers
  bool declared_linear = false;  ///< the metadata says linear values, or data that is not colour
};

/// An image file opened and its header read; its pixels are decoded on request.
class Decoder {
 public:
  /// Throws CodecError when `file` is not an image the codec reads.
  explicit Decoder(const std::filesystem::path& file);
  /// The same for an image file's bytes, which must outlive the decoder; `format` is an
  /// extension ("png", "jpeg") that a codec may use as a hint.
  Decoder(std::span<const unsigned char> bytes, const std::string& format);
  Decoder(Decoder&&) noexcept;
  ~Decoder();

  const Header& header() const { return header_; }

  /// The first `channels` channels (1 to 4) of every pixel as floats, row-major from the top
  /// row: values as stored, integers scaled to [0, 1]. Throws CodecError when the pixels cannot
  /// be decoded (a truncated or corrupt file).
  std::vector<float> read(int channels);

 private:
  struct State;
  Header header_;
  std::unique_ptr<State> state_;
};

/// The renders' primaries and white point, as OpenEXR's chromaticities attribute stores them
/// (red, green, blue, white; x then y): Rec. 709 with D65, the tracer's working space.
inline constexpr std::array<float, 8> kRec709Chromaticities = {0.64f, 0.33f, 0.30f,    0.60f,
                                                               0.15f, 0.06f, 0.3127f, 0.3290f};

/// A 32-bit float RGB OpenEXR file, ZIP compressed, tagged with kRec709Chromaticities, from 3
/// floats per pixel (top row first). Throws CodecError.
std::vector<unsigned char> encode_exr(std::uint32_t width, std::uint32_t height, const float* rgb);

/// An 8-bit RGB PNG file from 3 bytes per pixel (top row first). Throws CodecError.
std::vector<unsigned char> encode_png(std::uint32_t width, std::uint32_t height,
                                      const unsigned char* rgb);

}  // namespace trs::image_codec
