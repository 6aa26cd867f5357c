// Wavefront OBJ meshes, as trs-sample loads them.
#include "fuzz_input.h"
#include "scene_io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return trs_fuzz::parse_as_file(data, size, ".obj", [](const auto& path) { trs::load_mesh(path); });
}
