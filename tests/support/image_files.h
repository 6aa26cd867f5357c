#pragma once
// Image files for tests to read, written without the library under test: PNG by hand (so that
// every decoder is checked against an encoder of its own: 8 and 16 bits, 1 to 4 channels, any
// extra chunk), OpenEXR through OpenEXR (float channels, deep data), JPEG through
// stb_image_write.

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace trs_test {

/// A PNG chunk written before the pixels: its type ("gAMA") and data.
using PngChunk = std::pair<std::string, std::string>;

/// A PNG file's bytes: `samples` (`channels` per pixel: grey, grey and alpha, RGB or RGBA;
/// row-major, top row first) stored with `bit_depth` 8 or 16 bits, uncompressed.
std::string png_file(int width, int height, int channels, int bit_depth,
                     const std::vector<std::uint16_t>& samples,
                     const std::vector<PngChunk>& chunks = {});

/// Writes 32-bit float channels, `channels` per pixel (1: "Y"; 3: "R", "G", "B"), as OpenEXR:
/// scanlines, or square tiles of `tile` pixels.
void write_float_exr(const std::filesystem::path& file, int width, int height, int channels,
                     const std::vector<float>& values, int tile = 0);

/// An OpenEXR file's channels and compression, as "B:float G:float R:float, zip".
std::string exr_layout(const std::filesystem::path& file);

/// An OpenEXR file's chromaticities attribute (red, green, blue, white; x then y); empty when it
/// has none.
std::vector<float> exr_chromaticities(const std::filesystem::path& file);

/// Writes a 1 x 1 deep OpenEXR image: one pixel with two depth samples.
void write_deep_exr(const std::filesystem::path& file);

/// A JPEG file's bytes, from 3 bytes per pixel.
std::string jpeg_file(int width, int height, const std::vector<unsigned char>& rgb, int quality);

}  // namespace trs_test
