#pragma once
// A glTF 2.0 file (.gltf with its buffers, or .glb) as both glTF loaders read it: trs-sample's
// mesh loader and the tracer's scene loader. What is glTF's and not either loader's lives here:
// the node hierarchy with its world transforms, accessors located in their buffers with every
// range checked, and the triangles of strips and fans. Every failure is a FileError naming the
// file. Geometry is taken in its bind pose: skins and morph targets are not applied.

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace trs::gltf {

class Document {
 public:
  /// Parses the file and loads its buffers; .glb or .gltf by content, not by extension. Images
  /// are kept undecoded: embedded ones (buffer view or data URI) as their bytes in Image::image,
  /// external ones by their URI (see resolve_uri).
  explicit Document(std::filesystem::path file);

  const std::filesystem::path& file() const { return file_; }
  const tinygltf::Model& model() const { return model_; }

  [[noreturn]] void fail(const std::string& problem) const;
  /// Fails naming the first extension the file requires (extensionsRequired) that is not in
  /// `implemented`: a reader that ignored it would show something else than the file's author saw.
  void require_only(std::initializer_list<std::string_view> implemented) const;

  /// A relative URI of the document (percent-encoded, as glTF stores it) as a path.
  std::filesystem::path resolve_uri(const std::string& uri) const;

  using NodeVisitor =
      std::function<void(int index, const tinygltf::Node& node, const glm::dmat4& world)>;
  /// Every node of the default scene with its world matrix: depth first, parents before their
  /// children, siblings in the document's order.
  void for_each_node(const NodeVisitor& visit) const;

  /// `what` names the primitive in messages ("mesh 2 primitive 0").
  using PrimitiveVisitor = std::function<void(const tinygltf::Primitive& primitive,
                                              const glm::dmat4& world, const std::string& what)>;
  /// Every triangle primitive (triangles, strips, fans) of the nodes of for_each_node; points and
  /// lines have no area and are skipped.
  void for_each_triangle_primitive(const PrimitiveVisitor& visit) const;

  /// The primitive's POSITION (required, float VEC3), in its mesh's space.
  std::vector<glm::vec3> positions(const tinygltf::Primitive& primitive,
                                   const std::string& what) const;
  /// A float VEC3 attribute (NORMAL) with one element per vertex; nullopt where absent.
  std::optional<std::vector<glm::vec3>> vec3_attribute(const tinygltf::Primitive& primitive,
                                                       const std::string& name,
                                                       std::size_t vertex_count,
                                                       const std::string& what) const;
  /// A float VEC4 attribute (TANGENT) with one element per vertex; nullopt where absent.
  std::optional<std::vector<glm::vec4>> vec4_attribute(const tinygltf::Primitive& primitive,
                                                       const std::string& name,
                                                       std::size_t vertex_count,
                                                       const std::string& what) const;
  /// A VEC2 attribute (TEXCOORD_n) with one element per vertex: float, or normalized unsigned
  /// byte or short as glTF allows for texture coordinates; nullopt where absent.
  std::optional<std::vector<glm::vec2>> vec2_attribute(const tinygltf::Primitive& primitive,
                                                       const std::string& name,
                                                       std::size_t vertex_count,
                                                       const std::string& what) const;

  /// The primitive's triangles as vertex indices within the primitive, 3 per triangle, in the
  /// winding glTF defines for its mode; every index checked against `vertex_count`.
  std::vector<std::uint32_t> triangles(const tinygltf::Primitive& primitive,
                                       std::size_t vertex_count, const std::string& what) const;

  /// The index of the first of `added` vertices appended after `existing` ones: loaders index
  /// their vertices with 32 bits, and a file with more fails here rather than wrapping around.
  std::uint32_t vertex_base(std::size_t existing, std::size_t added) const;

  /// An animation channel that targets a property by JSON pointer (KHR_animation_pointer), such
  /// as "/materials/0/emissiveFactor". tinygltf reads only channels that target nodes, so these
  /// are read from the document's JSON here.
  struct PointerChannel {
    int animation;
    int sampler;  ///< of model().animations[animation]
    std::string pointer;
  };
  const std::vector<PointerChannel>& pointer_channels() const { return pointer_channels_; }

  /// A float SCALAR, VEC2, VEC3 or VEC4 accessor's values, `components` per element (an
  /// animation sampler's input or output): the accessor must have that many.
  std::vector<float> floats(int accessor, int components, const std::string& what) const;

 private:
  struct Accessor;
  Accessor locate(int index, const std::string& what) const;
  std::optional<Accessor> vertex_attribute(const tinygltf::Primitive& primitive,
                                           const std::string& name, std::size_t vertex_count,
                                           const std::string& what) const;
  /// A float VECN accessor's elements; `name` and `what` for messages.
  template <int N>
  std::vector<glm::vec<N, float>> float_vectors(const Accessor& data, const std::string& name,
                                                const std::string& what) const;
  template <int N>
  std::optional<std::vector<glm::vec<N, float>>> float_attribute(const tinygltf::Primitive& primitive,
                                                                 const std::string& name, std::size_t vertex_count,
                                                                 const std::string& what) const;
  std::vector<std::uint32_t> vertex_sequence(const tinygltf::Primitive& primitive,
                                             std::size_t vertex_count,
                                             const std::string& what) const;

  void read_pointer_channels();
  void read_pointer_channels(const nlohmann::json& animations);

  std::filesystem::path file_;
  tinygltf::Model model_;
  std::vector<PointerChannel> pointer_channels_;
};

}  // namespace trs::gltf
