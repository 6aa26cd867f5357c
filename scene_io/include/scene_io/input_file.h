#pragma once
// A first check of an input file, before a loader reads it: loaders report a missing file in their
// own words (or not at all), this says "no such file" the same way for every format.

#include <cstdint>
#include <filesystem>

namespace trs {

/// Throws FileError unless `file` is a regular file that this process can open for reading.
void check_input_file(const std::filesystem::path& file);

/// The most texels an input image (a density map, a texture) may have: 16384 x 16384, 1 GiB of
/// float densities.
inline constexpr std::uint64_t kMaxImageTexels = std::uint64_t(1) << 28;

/// Throws FileError when an image's header claims more than kMaxImageTexels: a header can claim
/// any size, so this runs before anything is allocated for it.
void check_image_size(const std::filesystem::path& file, int width, int height);

}  // namespace trs
