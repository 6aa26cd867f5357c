// Density maps through trs-sample's loading path (the image codec, then decoding and
// validation). The first byte picks the extension, so the corpus covers the formats users hand in.
#include "fuzz_input.h"
#include "scene_io/density_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const char* const kExtensions[] = {".exr", ".png", ".hdr", ".jpg", ".tif", ".pfm"};
  if (size == 0) return 0;
  const std::string extension = kExtensions[data[0] % std::size(kExtensions)];
  return trs_fuzz::parse_as_file(data + 1, size - 1, extension, [](const auto& path) {
    trs::load_density_map(path, trs::MapEncoding::automatic);
  });
}
