#pragma once
// Density maps from image files (EXR, HDR, PNG, JPEG, TIFF: anything OpenImageIO reads; in a build
// without it, the formats docs/renderer.md, "Images without OpenImageIO", lists).

#include <cstdint>
#include <filesystem>
#include <vector>

#include "lightsampler/mesh.h"

namespace trs {

/// How the file's values map to densities. `automatic`: 8- and 16-bit integer images are
/// sRGB-encoded unless their metadata says linear (or non-colour data; read with OpenImageIO
/// only); float images are linear.
enum class MapEncoding { automatic, srgb, linear };

/// A density map loaded from a file: one linear value per texel, row 0 = the image's top row
/// (the first row stored), which the library puts at v = 0.
struct DensityMap {
  std::filesystem::path file;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool srgb_decoded = false;  ///< the encoding that was applied
  std::vector<float> texels;  ///< width * height, row-major

  lightsampler::DensityMapView view(lightsampler::Addressing addressing, float scale) const;
};

/// Reads the first subimage: 1 channel is the value, 2 channels (grey, alpha) the first, 3 or
/// more the Rec. 709 luminance of the first three (R, G, B) after decoding to linear. Throws
/// FileError naming the file: unreadable, truncated, or a texel that is NaN, infinite or negative.
DensityMap load_density_map(const std::filesystem::path& file, MapEncoding encoding);

}  // namespace trs
