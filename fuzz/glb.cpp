// glTF 2.0 in its binary container (.glb), as trs-sample loads a mesh and trs-render a scene.
#include "fuzz_input.h"
#include "scene_io/mesh_io.h"
#include "tracer/gltf_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  trs_fuzz::parse_as_file(data, size, ".glb", [](const auto& path) { trs::load_mesh(path); });
  return trs_fuzz::parse_as_file(data, size, ".glb", [](const auto& path) { tracer::load_gltf_scene(path); });
}
