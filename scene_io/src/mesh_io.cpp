#include "scene_io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>

#include "scene_io/file_error.h"
#include "scene_io/input_file.h"
#include "scene_io/mesh_loaders.h"

namespace trs {
namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

/// What every format must satisfy before the sampler sees the mesh. Only vertices that triangles
/// use are checked: an unused vertex with garbage in it harms nobody.
void check_mesh(const MeshData& mesh) {
  if (mesh.indices.empty()) throw FileError(mesh.file, "no triangles");
  const std::size_t vertex_count = mesh.positions.size() / 3;
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    const std::uint32_t v = mesh.indices[i];
    const std::string where = "triangle " + std::to_string(i / 3);
    if (v >= vertex_count) {
      throw FileError(mesh.file, where + " uses vertex " + std::to_string(v) + " of " +
                                     std::to_string(vertex_count));
    }
    const float* p = &mesh.positions[3 * std::size_t(v)];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw FileError(mesh.file, where + ": vertex " + std::to_string(v) + " has a non-finite position");
    }
    const float* t = &mesh.uvs[2 * std::size_t(v)];
    if (!std::isfinite(t[0]) || !std::isfinite(t[1])) {
      throw FileError(mesh.file, where + ": vertex " + std::to_string(v) + " has a non-finite UV");
    }
  }
}

}  // namespace

lightsampler::MeshView MeshData::view() const {
  return {.positions = positions, .uvs = uvs, .indices = indices, .triangle_maps = {}};
}

MeshData load_mesh(const std::filesystem::path& file) {
  check_input_file(file);
  const std::string extension = lower_extension(file);
  MeshData mesh;
  if (extension == ".obj") {
    mesh = load_obj(file);
  } else if (extension == ".gltf" || extension == ".glb") {
    mesh = load_gltf(file);
  } else {
    throw FileError(file, "unknown mesh format '" + extension + "' (expected .obj, .gltf or .glb)");
  }
  check_mesh(mesh);
  return mesh;
}

MeshData load_gltf_material(const std::filesystem::path& file, int material) {
  check_input_file(file);
  MeshData mesh = load_gltf(file, material);
  if (mesh.indices.empty())
    throw FileError(file, "no triangle uses material " + std::to_string(material));
  check_mesh(mesh);
  return mesh;
}

lightsampler::Float2 to_file_uv(lightsampler::Float2 uv, UvOrigin origin) {
  return origin == UvOrigin::top ? uv : lightsampler::Float2{uv.x, 1.0f - uv.y};
}

}  // namespace trs
