#include "scene_io/gltf_document.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <utility>

#include <nlohmann/json.hpp>

#include "scene_io/file_error.h"

namespace trs::gltf {
namespace {

/// A node's local transform: its matrix, or T * R * S.
glm::dmat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());  // column-major
  glm::dmat4 m(1.0);
  if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
  if (node.rotation.size() == 4) {
    const auto& q = node.rotation;  // x, y, z, w
    m *= glm::mat4_cast(glm::dquat(q[3], q[0], q[1], q[2]));
  }
  if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
  return m;
}

template <class T>
T load(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

/// Keeps images undecoded: the loaders decode what they need themselves (the mesh loader nothing,
/// the tracer through scene_io's image codec). tinygltf hands over the bytes of external images
/// too; those are dropped, as the image is read from its file.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->uri.empty()) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

bool has_binary_magic(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
}

/// tinygltf's messages on one line.
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' '))
    text.pop_back();
  for (char& c : text) {
    if (c == '\n') c = ';';
  }
  return text;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

/// The elements of an accessor, located in their buffer and bounds-checked.
struct Document::Accessor {
  const unsigned char* first = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;

  const unsigned char* element(std::size_t i) const { return first + i * stride; }
};

Document::Document(std::filesystem::path file) : file_(std::move(file)) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_image_bytes, nullptr);
  std::string error, warning;
  // The content decides, not the extension: .glb files renamed .gltf are common enough.
  const bool ok = has_binary_magic(file_)
                      ? loader.LoadBinaryFromFile(&model_, &error, &warning, file_.string())
                      : loader.LoadASCIIFromFile(&model_, &error, &warning, file_.string());
  if (!ok) fail("malformed glTF: " + one_line(error.empty() ? warning : error));
  read_pointer_channels();
  for (const std::string& extension : model_.extensionsRequired) {
    if (extension == "KHR_draco_mesh_compression" || extension == "EXT_meshopt_compression" ||
        extension == "KHR_mesh_quantization") {
      fail("requires " + extension + ", which is not supported");
    }
  }
}

void Document::fail(const std::string& problem) const { throw FileError(file_, problem); }

void Document::require_only(std::initializer_list<std::string_view> implemented) const {
  for (const std::string& extension : model_.extensionsRequired) {
    if (std::find(implemented.begin(), implemented.end(), extension) == implemented.end())
      fail("requires the extension " + extension + ", which is not implemented");
  }
}

void Document::read_pointer_channels() {
  const bool used = std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(),
                              "KHR_animation_pointer") != model_.extensionsUsed.end();
  if (!used) return;
  std::ifstream in(file_, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (has_binary_magic(file_)) {
    // A .glb's first chunk is its JSON: header 12 bytes, then chunk length and type (8 bytes).
    if (text.size() < 20) fail("malformed glTF: truncated binary header");
    text = text.substr(20, load<std::uint32_t>(reinterpret_cast<const unsigned char*>(text.data()) + 12));
  }
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
  if (json.is_discarded() || !json.is_object() || !json.contains("animations")) return;  // none
  const nlohmann::json& animations = json["animations"];
  if (!animations.is_array() || animations.size() != model_.animations.size())
    fail("malformed glTF: its animations are not an array that tinygltf read whole");
  // A value of the wrong type (a channel that is no object, say) throws from nlohmann's accessors.
  try {
    read_pointer_channels(animations);
  } catch (const nlohmann::json::exception&) {
    fail("malformed glTF: an animation channel is not an object with a target and a sampler");
  }
}

void Document::read_pointer_channels(const nlohmann::json& animations) {
  for (std::size_t a = 0; a < animations.size(); ++a) {
    const nlohmann::json& channels = animations[a].value("channels", nlohmann::json::array());
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const nlohmann::json pointer = channels[c].value("target", nlohmann::json::object())
                                         .value("extensions", nlohmann::json::object())
                                         .value("KHR_animation_pointer", nlohmann::json::object())
                                         .value("pointer", nlohmann::json());
      if (!pointer.is_string()) continue;
      const std::string what = "animation " + std::to_string(a) + " channel " + std::to_string(c);
      const nlohmann::json& sampler = channels[c].value("sampler", nlohmann::json());
      if (!sampler.is_number_integer() || sampler.get<std::int64_t>() < 0 ||
          std::size_t(sampler.get<std::int64_t>()) >= model_.animations[a].samplers.size())
        fail(what + ": its sampler does not exist");
      pointer_channels_.push_back({int(a), int(sampler.get<std::int64_t>()), pointer.get<std::string>()});
    }
  }
}

std::vector<float> Document::floats(int accessor, int components, const std::string& what) const {
  const Accessor data = locate(accessor, what);
  if (data.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT || data.components != components)
    fail(what + ": accessor " + std::to_string(accessor) + " must hold " + std::to_string(components) +
         " float" + (components > 1 ? "s" : "") + " per element");
  std::vector<float> values;
  values.reserve(data.count * std::size_t(components));
  for (std::size_t i = 0; i < data.count; ++i)
    for (int k = 0; k < components; ++k) values.push_back(load<float>(data.element(i) + 4 * k));
  return values;
}

std::filesystem::path Document::resolve_uri(const std::string& uri) const {
  std::string decoded;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    const int high = uri[i] == '%' && i + 2 < uri.size() ? hex_digit(uri[i + 1]) : -1;
    const int low = high >= 0 ? hex_digit(uri[i + 2]) : -1;
    if (low >= 0) {
      decoded += static_cast<char>(high * 16 + low);
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  return file_.parent_path() / decoded;
}

void Document::for_each_node(const NodeVisitor& visit) const {
  if (model_.scenes.empty()) fail("no scene");
  const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
  if (std::size_t(scene) >= model_.scenes.size())
    fail("default scene " + std::to_string(scene) + " does not exist");
  // Depth first with an explicit stack (a deep hierarchy must not overflow the call stack),
  // pushed in reverse so that siblings come off in their order.
  std::vector<std::pair<int, glm::dmat4>> pending;
  const std::vector<int>& roots = model_.scenes[std::size_t(scene)].nodes;
  for (auto root = roots.rbegin(); root != roots.rend(); ++root)
    pending.emplace_back(*root, glm::dmat4(1.0));
  std::vector<bool> visited(model_.nodes.size(), false);
  while (!pending.empty()) {
    const auto [index, parent] = pending.back();
    pending.pop_back();
    if (index < 0 || std::size_t(index) >= model_.nodes.size())
      fail("node " + std::to_string(index) + " does not exist");
    // glTF nodes form a forest; a second visit means a cycle or a shared child, either of which
    // would otherwise loop forever or multiply the geometry.
    if (visited[std::size_t(index)])
      fail("node " + std::to_string(index) + " has more than one parent (or is in a cycle)");
    visited[std::size_t(index)] = true;
    const tinygltf::Node& node = model_.nodes[std::size_t(index)];
    const glm::dmat4 world = parent * local_transform(node);
    visit(index, node, world);
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
      pending.emplace_back(*child, world);
  }
}

void Document::for_each_triangle_primitive(const PrimitiveVisitor& visit) const {
  for_each_node([&](int index, const tinygltf::Node& node, const glm::dmat4& world) {
    if (node.mesh < 0) return;
    if (std::size_t(node.mesh) >= model_.meshes.size())
      fail("node " + std::to_string(index) + " uses mesh " + std::to_string(node.mesh) +
           ", which does not exist");
    const auto& primitives = model_.meshes[std::size_t(node.mesh)].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const int mode = primitives[p].mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        continue;
      }
      visit(primitives[p], world,
            "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p));
    }
  });
}

Document::Accessor Document::locate(int index, const std::string& what) const {
  if (index < 0 || std::size_t(index) >= model_.accessors.size())
    fail(what + ": accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& accessor = model_.accessors[std::size_t(index)];
  if (accessor.sparse.isSparse) fail(what + ": sparse accessors are not supported");
  if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= model_.bufferViews.size())
    fail(what + ": accessor " + std::to_string(index) + " has no buffer view");
  const tinygltf::BufferView& view = model_.bufferViews[std::size_t(accessor.bufferView)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
    fail(what + ": buffer view refers to a missing buffer");
  const tinygltf::Buffer& buffer = model_.buffers[std::size_t(view.buffer)];

  Accessor data;
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
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset)
    fail(what + ": buffer view extends past the end of its buffer (truncated buffer?)");
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

std::optional<Document::Accessor> Document::vertex_attribute(const tinygltf::Primitive& primitive,
                                                             const std::string& name,
                                                             std::size_t vertex_count,
                                                             const std::string& what) const {
  const auto attribute = primitive.attributes.find(name);
  if (attribute == primitive.attributes.end()) return std::nullopt;
  const Accessor data = locate(attribute->second, what + " " + name);
  if (data.count != vertex_count) fail(what + ": " + name + " and POSITION have different counts");
  return data;
}

template <int N>
std::vector<glm::vec<N, float>> Document::float_vectors(const Accessor& data, const std::string& name,
                                                        const std::string& what) const {
  if (data.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT || data.components != N)
    fail(what + ": " + name + " must be float VEC" + std::to_string(N));
  std::vector<glm::vec<N, float>> values(data.count);
  for (std::size_t i = 0; i < data.count; ++i) {
    const unsigned char* e = data.element(i);
    for (int k = 0; k < N; ++k) values[i][k] = load<float>(e + 4 * k);
  }
  return values;
}

template <int N>
std::optional<std::vector<glm::vec<N, float>>> Document::float_attribute(const tinygltf::Primitive& primitive,
                                                                         const std::string& name,
                                                                         std::size_t vertex_count,
                                                                         const std::string& what) const {
  const auto data = vertex_attribute(primitive, name, vertex_count, what);
  if (!data) return std::nullopt;
  return float_vectors<N>(*data, name, what);
}

std::vector<glm::vec3> Document::positions(const tinygltf::Primitive& primitive,
                                           const std::string& what) const {
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) fail(what + " has no POSITION");
  return float_vectors<3>(locate(position->second, what + " POSITION"), "POSITION", what);
}

std::optional<std::vector<glm::vec3>> Document::vec3_attribute(const tinygltf::Primitive& primitive,
                                                               const std::string& name,
                                                               std::size_t vertex_count,
                                                               const std::string& what) const {
  return float_attribute<3>(primitive, name, vertex_count, what);
}

std::optional<std::vector<glm::vec4>> Document::vec4_attribute(const tinygltf::Primitive& primitive,
                                                               const std::string& name,
                                                               std::size_t vertex_count,
                                                               const std::string& what) const {
  return float_attribute<4>(primitive, name, vertex_count, what);
}

std::optional<std::vector<glm::vec2>> Document::vec2_attribute(const tinygltf::Primitive& primitive,
                                                               const std::string& name,
                                                               std::size_t vertex_count,
                                                               const std::string& what) const {
  const auto data = vertex_attribute(primitive, name, vertex_count, what);
  if (!data) return std::nullopt;
  const int type = data->component_type;
  const bool is_float = type == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_u8 = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && data->normalized;
  const bool is_u16 = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && data->normalized;
  if (data->components != 2 || (!is_float && !is_u8 && !is_u16))
    fail(what + ": " + name + " must be VEC2 of float, or of normalized unsigned byte or short");
  auto component = [&](const unsigned char* e, int k) {
    if (is_float) return load<float>(e + 4 * k);
    if (is_u8) return float(e[k]) / 255.0f;
    return float(load<std::uint16_t>(e + 2 * k)) / 65535.0f;
  };
  std::vector<glm::vec2> values(data->count);
  for (std::size_t i = 0; i < data->count; ++i) {
    const unsigned char* e = data->element(i);
    values[i] = {component(e, 0), component(e, 1)};
  }
  return values;
}

/// The primitive's vertex sequence: its indices, or 0, 1, ... without them.
std::vector<std::uint32_t> Document::vertex_sequence(const tinygltf::Primitive& primitive,
                                                     std::size_t vertex_count,
                                                     const std::string& what) const {
  std::vector<std::uint32_t> sequence;
  if (primitive.indices < 0) {
    sequence.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) sequence[i] = static_cast<std::uint32_t>(i);
    return sequence;
  }
  const Accessor indices = locate(primitive.indices, what + " indices");
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

std::vector<std::uint32_t> Document::triangles(const tinygltf::Primitive& primitive,
                                               std::size_t vertex_count,
                                               const std::string& what) const {
  const std::vector<std::uint32_t> v = vertex_sequence(primitive, vertex_count, what);
  std::vector<std::uint32_t> corners;
  auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
    corners.insert(corners.end(), {v[a], v[b], v[c]});
  };
  if (primitive.mode == TINYGLTF_MODE_TRIANGLES) {
    if (v.size() % 3 != 0)
      fail(what + ": " + std::to_string(v.size()) + " vertices is not a whole number of triangles");
    corners = v;
  } else if (primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // Every other triangle flips its winding.
    for (std::size_t i = 0; i + 2 < v.size(); ++i) emit(i, i + 1 + i % 2, i + 2 - i % 2);
  } else {
    for (std::size_t i = 0; i + 2 < v.size(); ++i) emit(i + 1, i + 2, 0);
  }
  return corners;
}

std::uint32_t Document::vertex_base(std::size_t existing, std::size_t added) const {
  constexpr std::size_t kMost = std::numeric_limits<std::uint32_t>::max();
  if (existing > kMost || added > kMost - existing) fail("more than 2^32 - 1 vertices");
  return static_cast<std::uint32_t>(existing);
}

}  // namespace trs::gltf
