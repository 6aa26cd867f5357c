#pragma once
// RGB images in and out of the tools, through the build's image codec (OpenImageIO, or stb_image
// and OpenEXR: TRS_OPENIMAGEIO): the renderer's linear EXR outputs and their PNG previews,
// written atomically (complete or not at all, like every output of the tools), and images read
// back as RGB floats (renders to compare, textures).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "scene_io/display.h"

namespace trs {

struct Image {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> rgb;  ///< 3 per pixel, row-major, row 0 = the image's top row
  /// 1 per pixel, as stored (never sRGB-encoded), where it was asked for and the file has it;
  /// else empty.
  std::vector<float> alpha;
  /// The file stores 8- or 16-bit integers: colour stored so is display-encoded (sRGB) by
  /// convention, whereas float files hold linear values. The values here are as stored.
  bool integer = false;
};

/// Writes linear Rec. 709 RGB (3 floats per pixel, top row first) as a 32-bit float OpenEXR file,
/// ZIP compressed, so that reading it back gives the same floats; its chromaticities attribute
/// says Rec. 709 primaries and D65 white. Throws FileError naming `file`.
void write_exr(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               const float* rgb);

/// Linear Rec. 709 RGB (`count` floats) for viewing: scaled by 2^exposure, encoded by `display`
/// (by default the sRGB curve), clamped to [0, 1] (NaN to 0) and rounded to 8 bits.
std::vector<unsigned char> preview_rgb8(const float* rgb, std::size_t count, float exposure = 0.0f,
                                        const DisplayEncoder& display = DisplayEncoder());

/// Writes preview_rgb8 of linear Rec. 709 RGB as an 8-bit RGB PNG. Throws FileError naming `file`.
void write_png_preview(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
                       const float* rgb, float exposure = 0.0f,
                       const DisplayEncoder& display = DisplayEncoder());

/// Writes 8-bit RGB display values (3 per pixel, top row first) as they are, for an sRGB display
/// (OpenImageIO tags the file sRGB; an untagged PNG means the same): a false-colour map, say.
/// Throws FileError naming `file`.
void write_png(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               const unsigned char* rgb);

/// Reads an OpenEXR file's first three channels (one grey channel is repeated); another format
/// is an error, as comparing renders through an 8-bit file would compare its rounding.
Image read_exr(const std::filesystem::path& file);

/// Whether reading an image keeps its alpha channel.
enum class Alpha : bool { drop, keep };

/// Reads any image the codec decodes: the first subimage's R, G, B (grey repeated), and its
/// alpha where `alpha` keeps it.
Image read_image(const std::filesystem::path& file, Alpha alpha = Alpha::drop);

/// The width and height of an image file, from its header alone. Throws FileError naming
/// `file`, as read_image.
std::pair<std::uint32_t, std::uint32_t> image_size(const std::filesystem::path& file);

/// The same for an image file's bytes embedded in `file` (a glTF buffer or data URI); `format`
/// is an extension ("png", "jpeg") and `what` names the image in messages. Formats that the
/// codec cannot read from memory are an error: nothing is written to disk.
Image read_image(std::span<const unsigned char> bytes, const std::string& format,
                 const std::filesystem::path& file, const std::string& what, Alpha alpha = Alpha::drop);

}  // namespace trs
