#pragma once
// A first check of an input file, before a loader reads it: loaders report a missing file in their
// own words (or not at all), this says "no such file" the same way for every format.

#include <cstdint>
#include <filesystem>

namespace trs {

/// Throws FileError unless `file` is a regular file that this process can open for reading.
void check_input_file(const std::filesystem::path& file);

/// The longest side an input image (a density map, a texture) may have: 16384 x 16384 is 1 GiB of
/// float densities, and the largest 2D image many GPUs take. A side is bounded, not only the area,
/// because decoders size their buffers by the row: a 1-texel-high image millions wide costs
/// gigabytes before its first row is read.
inline constexpr int kMaxImageSide = 16384;

/// Throws FileError when an image's header claims a side longer than kMaxImageSide: a header can
/// claim any size, so this runs before anything is allocated for it.
void check_image_size(const std::filesystem::path& file, int width, int height);

}  // namespace trs
