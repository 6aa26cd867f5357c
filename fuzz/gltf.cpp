// glTF 2.0 in its JSON form, as trs-sample loads a mesh and trs-render a scene (materials,
// textures, cameras, node hierarchy).
#include "fuzz_input.h"
#include "scene_io/mesh_io.h"
#include "tracer/gltf_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  trs_fuzz::parse_as_file(data, size, ".gltf", [](const auto& path) { trs::load_mesh(path); });
  return trs_fuzz::parse_as_file(data, size, ".gltf", [](const auto& path) { tracer::load_gltf_scene(path); });
}
