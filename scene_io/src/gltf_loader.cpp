// glTF 2.0 (.gltf with its buffers, or .glb): every triangle primitive of the default scene's
// node hierarchy, in world space, with its TEXCOORD_0. glTF's UV convention is the library's, so
// UVs pass unchanged. Reading the file itself is gltf::Document's.

#include "scene_io/gltf_document.h"
#include "scene_io/mesh_loaders.h"

namespace trs {

MeshData load_gltf(const std::filesystem::path& file, std::optional<int> material) {
  const gltf::Document document(file);
  MeshData mesh;
  mesh.file = file;
  mesh.file_uv_origin = UvOrigin::top;
  document.for_each_triangle_primitive([&](const tinygltf::Primitive& primitive,
                                           const glm::dmat4& world, const std::string& what) {
    if (material && primitive.material != *material) return;
    const std::vector<glm::vec3> positions = document.positions(primitive, what);
    const auto uvs = document.vec2_attribute(primitive, "TEXCOORD_0", positions.size(), what);
    if (!uvs) document.fail(what + " has no TEXCOORD_0 (UVs are required)");
    const std::uint32_t base = document.vertex_base(mesh.positions.size() / 3, positions.size());
    for (const glm::vec3& p : positions) {
      const glm::vec3 q(world * glm::dvec4(p, 1.0));
      mesh.positions.insert(mesh.positions.end(), {q.x, q.y, q.z});
    }
    for (const glm::vec2& uv : *uvs) mesh.uvs.insert(mesh.uvs.end(), {uv.x, uv.y});
    for (const std::uint32_t v : document.triangles(primitive, positions.size(), what))
      mesh.indices.push_back(base + v);
  });
  return mesh;
}

}  // namespace trs
