// glTF 2.0 (.gltf with its buffers, or .glb): every triangle primitive of the default scene's
// node hierarchy, in world space. glTF's UV convention is the library's, so UVs pass unchanged.
// Geometry is taken in its bind pose: skins and morph targets are not applied.

#include <tiny_gltf.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/file_error.h"
#include "common/mesh_loaders.h"

namespace trs {
namespace {

using Matrix = std::array<double, 16>;  // column-major, as glTF stores it
constexpr Matrix kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int col = 0; col < 4; ++col) {
    for (int row = 0; row < 4; ++row) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a[k * 4 + row] * b[col * 4 + k];
      c[col * 4 + row] = sum;
    }
  }
  return c;
}

/// A node's local transform: its matrix, or T * R * S.
Matrix local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    Matrix m;
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
    return m;
  }
  const auto& t = node.translation;
  const auto& r = node.rotation;  // quaternion x, y, z, w
  const auto& s = node.scale;
  const double tx = t.size() == 3 ? t[0] : 0, ty = t.size() == 3 ? t[1] : 0,
               tz = t.size() == 3 ? t[2] : 0;
  const double qx = r.size() == 4 ? r[0] : 0, qy = r.size() == 4 ? r[1] : 0;
  const double qz = r.size() == 4 ? r[2] : 0, qw = r.size() == 4 ? r[3] : 1;
  const double sx = s.size() == 3 ? s[0] : 1, sy = s.size() == 3 ? s[1] : 1,
               sz = s.size() == 3 ? s[2] : 1;
  const double rot[9] = {
      // column-major 3x3 of the unit quaternion
      1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy + qz * qw),     2 * (qx * qz - qy * qw),
      2 * (qx * qy - qz * qw),     1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + qx * qw),
      2 * (qx * qz + qy * qw),     2 * (qy * qz - qx * qw),     1 - 2 * (qx * qx + qy * qy)};
  return {rot[0] * sx, rot[1] * sx, rot[2] * sx, 0, rot[3] * sy, rot[4] * sy, rot[5] * sy, 0,
          rot[6] * sz, rot[7] * sz, rot[8] * sz, 0, tx,          ty,          tz,          1};
}

/// The elements of an accessor, located in their buffer and bounds-checked.
struct AccessorData {
  const unsigned char* first = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;

  const unsigned char* element(std::size_t i) const { return first + i * stride; }
};

template <class T>
T load(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

class GltfReader {
 public:
  GltfReader(const std::filesystem::path& file, const tinygltf::Model& model, MeshData& mesh)
      : file_(file), model_(model), mesh_(mesh) {}

  void read_scene() {
    if (model_.scenes.empty()) fail("no scene");
    const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (std::size_t(scene) >= model_.scenes.size())
      fail("default scene " + std::to_string(scene) + " does not exist");
    // Depth first with an explicit stack: a deep hierarchy must not overflow the call stack.
    std::vector<std::pair<int, Matrix>> pending;
    for (const int node : model_.scenes[std::size_t(scene)].nodes)
      pending.emplace_back(node, kIdentity);
    std::vector<bool> visited(model_.nodes.size(), false);
    while (!pending.empty()) {
      const auto [index, parent] = pending.back();
      pending.pop_back();
      if (index < 0 || std::size_t(index) >= model_.nodes.size())
        fail("node " + std::to_string(index) + " does not exist");
      // glTF nodes form a forest; a second visit means a cycle or a shared child, either of
      // which would otherwise loop forever or multiply the geometry.
      if (visited[std::size_t(index)])
        fail("node " + std::to_string(index) + " has more than one parent (or is in a cycle)");
      visited[std::size_t(index)] = true;
      const tinygltf::Node& node = model_.nodes[std::size_t(index)];
      const Matrix world = multiply(parent, local_transform(node));
      if (node.mesh >= 0) read_mesh(index, node.mesh, world);
      for (const int child : node.children) pending.emplace_back(child, world);
    }
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw FileError(file_, problem); }

  void read_mesh(int node, int mesh, const Matrix& world) {
    if (std::size_t(mesh) >= model_.meshes.size())
      fail("node " + std::to_string(node) + " uses mesh " + std::to_string(mesh) +
           ", which does not exist");
    const auto& primitives = model_.meshes[std::size_t(mesh)].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      read_primitive(primitives[p], world,
                     "mesh " + std::to_string(mesh) + " primitive " + std::to_string(p));
    }
  }

  AccessorData locate(int index, const std::string& what) const {
    if (index < 0 || std::size_t(index) >= model_.accessors.size())
      fail(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[std::size_t(index)];
    if (accessor.sparse.isSparse) fail(what + ": sparse accessors are not supported");
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= model_.bufferViews.size()) {
      fail(what + ": accessor " + std::to_string(index) + " has no buffer view");
    }
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(accessor.bufferView)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
      fail(what + ": buffer view refers to a missing buffer");
    const tinygltf::Buffer& buffer = model_.buffers[std::size_t(view.buffer)];

    AccessorData data;
    data.count = accessor.count;
    data.component_type = accessor.componentType;
    data.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
    data.normalized = accessor.normalized;
    const int component_size =
        tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
    if (data.components <= 0 || component_size <= 0)
      fail(what + ": accessor " + std::to_string(index) + " has an invalid type");
    const std::size_t element_size = std::size_t(data.components) * std::size_t(component_size);
    data.stride = view.byteStride != 0 ? view.byteStride : element_size;
    if (data.stride < element_size) fail(what + ": buffer view stride is smaller than an element");

    // Overflow-safe form of: view and accessor ranges lie within their containers.
    const std::size_t buffer_size = buffer.data.size();
    if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
      fail(what + ": buffer view extends past the end of its buffer (truncated buffer?)");
    }
    if (data.count > 0) {
      const std::size_t span =
          (data.count - 1) > (std::numeric_limits<std::size_t>::max() - element_size) / data.stride
              ? std::numeric_limits<std::size_t>::max()
              : (data.count - 1) * data.stride + element_size;
      if (accessor.byteOffset > view.byteLength || span > view.byteLength - accessor.byteOffset) {
        fail(what + ": accessor " + std::to_string(index) +
             " extends past the end of its buffer view");
      }
    }
    data.first = buffer.data.data() + view.byteOffset + accessor.byteOffset;
    return data;
  }

  void read_primitive(const tinygltf::Primitive& primitive, const Matrix& world,
                      const std::string& what) {
    const int mode = primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      return;  // points and lines have no area to sample
    }
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail(what + " has no POSITION");
    const auto texcoord = primitive.attributes.find("TEXCOORD_0");
    if (texcoord == primitive.attributes.end())
      fail(what + " has no TEXCOORD_0 (UVs are required)");

    const AccessorData positions = locate(position->second, what + " POSITION");
    if (positions.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT || positions.components != 3) {
      fail(what + ": POSITION must be float VEC3");
    }
    const AccessorData uvs = locate(texcoord->second, what + " TEXCOORD_0");
    if (uvs.components != 2) fail(what + ": TEXCOORD_0 must be VEC2");
    if (uvs.count != positions.count)
      fail(what + ": TEXCOORD_0 and POSITION have different counts");
    const std::size_t base = mesh_.positions.size() / 3;
    if (positions.count > std::numeric_limits<std::uint32_t>::max() - base)
      fail("more than 2^32 - 1 vertices");

    append_positions(positions, world);
    append_uvs(uvs, what);
    append_triangles(primitive, mode, positions.count, static_cast<std::uint32_t>(base), what);
  }

  void append_positions(const AccessorData& positions, const Matrix& m) {
    for (std::size_t i = 0; i < positions.count; ++i) {
      const unsigned char* e = positions.element(i);
      const double x = load<float>(e), y = load<float>(e + 4), z = load<float>(e + 8);
      mesh_.positions.push_back(static_cast<float>(m[0] * x + m[4] * y + m[8] * z + m[12]));
      mesh_.positions.push_back(static_cast<float>(m[1] * x + m[5] * y + m[9] * z + m[13]));
      mesh_.positions.push_back(static_cast<float>(m[2] * x + m[6] * y + m[10] * z + m[14]));
    }
  }

  void append_uvs(const AccessorData& uvs, const std::string& what) {
    const int type = uvs.component_type;
    const bool is_float = type == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool is_u8 = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && uvs.normalized;
    const bool is_u16 = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && uvs.normalized;
    if (!is_float && !is_u8 && !is_u16)
      fail(what + ": TEXCOORD_0 must be float, or normalized unsigned byte or short");
    for (std::size_t i = 0; i < uvs.count; ++i) {
      const unsigned char* e = uvs.element(i);
      for (int k = 0; k < 2; ++k) {
        if (is_float) {
          mesh_.uvs.push_back(load<float>(e + 4 * k));
        } else if (is_u8) {
          mesh_.uvs.push_back(float(e[k]) / 255.0f);
        } else {
          mesh_.uvs.push_back(float(load<std::uint16_t>(e + 2 * k)) / 65535.0f);
        }
      }
    }
  }

  /// The primitive's vertex sequence: its indices, or 0, 1, ... without them.
  std::vector<std::uint32_t> vertex_sequence(const tinygltf::Primitive& primitive,
                                             std::size_t vertex_count,
                                             const std::string& what) const {
    std::vector<std::uint32_t> sequence;
    if (primitive.indices < 0) {
      sequence.resize(vertex_count);
      for (std::size_t i = 0; i < vertex_count; ++i) sequence[i] = static_cast<std::uint32_t>(i);
      return sequence;
    }
    const AccessorData indices = locate(primitive.indices, what + " indices");
    if (indices.components != 1) fail(what + ": indices must be SCALAR");
    sequence.resize(indices.count);
    for (std::size_t i = 0; i < indices.count; ++i) {
      const unsigned char* e = indices.element(i);
      switch (indices.component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          sequence[i] = e[0];
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
          sequence[i] = load<std::uint16_t>(e);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
          sequence[i] = load<std::uint32_t>(e);
          break;
        default:
          fail(what + ": indices must be unsigned byte, short or int");
      }
      if (sequence[i] >= vertex_count) {
        fail(what + ": index " + std::to_string(i) + " is " + std::to_string(sequence[i]) +
             ", but the primitive has " + std::to_string(vertex_count) + " vertices");
      }
    }
    return sequence;
  }

  void append_triangles(const tinygltf::Primitive& primitive, int mode, std::size_t vertex_count,
                        std::uint32_t base, const std::string& what) {
    const std::vector<std::uint32_t> v = vertex_sequence(primitive, vertex_count, what);
    auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
      mesh_.indices.insert(mesh_.indices.end(), {base + v[a], base + v[b], base + v[c]});
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (v.size() % 3 != 0)
        fail(what + ": " + std::to_string(v.size()) +
             " vertices is not a whole number of triangles");
      for (std::size_t i = 0; i + 2 < v.size(); i += 3) emit(i, i + 1, i + 2);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // every other triangle flips its winding
      for (std::size_t i = 0; i + 2 < v.size(); ++i) emit(i, i + 1 + i % 2, i + 2 - i % 2);
    } else {
      for (std::size_t i = 0; i + 2 < v.size(); ++i) emit(i + 1, i + 2, 0);
    }
  }

  const std::filesystem::path& file_;
  const tinygltf::Model& model_;
  MeshData& mesh_;
};

/// Images are materials' business, not the mesh's: accept them undecoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

bool has_binary_magic(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
}

std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' '))
    text.pop_back();
  for (char& c : text) {
    if (c == '\n') c = ';';
  }
  return text;
}

}  // namespace

MeshData load_gltf(const std::filesystem::path& file) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  // The content decides, not the extension: .glb files renamed .gltf are common enough.
  const bool ok = has_binary_magic(file)
                      ? loader.LoadBinaryFromFile(&model, &error, &warning, file.string())
                      : loader.LoadASCIIFromFile(&model, &error, &warning, file.string());
  if (!ok) throw FileError(file, "malformed glTF: " + trimmed(error.empty() ? warning : error));
  for (const std::string& extension : model.extensionsRequired) {
    if (extension == "KHR_draco_mesh_compression" || extension == "EXT_meshopt_compression" ||
        extension == "KHR_mesh_quantization") {
      throw FileError(file, "requires " + extension + ", which is not supported");
    }
  }
  MeshData mesh;
  mesh.file = file;
  mesh.file_uv_origin = UvOrigin::top;
  GltfReader(file, model, mesh).read_scene();
  return mesh;
}

}  // namespace trs
