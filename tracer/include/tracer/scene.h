#pragma once
// A scene as the tracer renders it: one world-space triangle mesh, its materials and textures
// (linear, decoded at load time), and a camera. Loaders fill it; nothing here knows glTF.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tracer {

/// How texture coordinates outside [0, 1] are brought back, per axis (glTF sampler wrap modes).
enum class Wrap : std::uint8_t { repeat, clamp, mirrored_repeat };

/// Linear RGB texels, row-major, row 0 at v = 0 (glTF's convention: the image's top row).
/// Colour textures are decoded from their encoding (sRGB) to linear Rec.709 at load time; data
/// textures (metallic-roughness) keep their values.
struct Texture {
  std::string name;  ///< for messages: the image's URI or name
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec3> texels;  ///< width * height
  Wrap wrap_s = Wrap::repeat;
  Wrap wrap_t = Wrap::repeat;
  /// glTF's magnification filter asked for nearest. Emission is always read nearest (texel for
  /// texel with the light sampler); other textures are bilinear unless this is set.
  bool nearest = false;
};

inline constexpr std::int32_t kNoTexture = -1;

/// glTF's metallic-roughness material. Texture channels as glTF defines them: base colour RGB;
/// roughness in G, metallic in B of the metallic-roughness texture.
struct Material {
  std::string name;
  glm::vec3 base_color{1.0f};
  std::int32_t base_color_texture = kNoTexture;
  float metallic = 1.0f;
  float roughness = 1.0f;
  std::int32_t metallic_roughness_texture = kNoTexture;
  /// Emitted radiance = emissive_factor * emissive texture * emissive_strength
  /// (KHR_materials_emissive_strength), in linear Rec.709.
  glm::vec3 emissive_factor{0.0f};
  std::int32_t emissive_texture = kNoTexture;
  float emissive_strength = 1.0f;
  /// Single-sided surfaces emit from their front face only (counter-clockwise winding).
  bool double_sided = false;

  bool emissive() const {
    return emissive_strength > 0.0f &&
           (emissive_factor.r > 0.0f || emissive_factor.g > 0.0f || emissive_factor.b > 0.0f);
  }
};

/// Every triangle of the scene in world space. Vertices are not shared between primitives.
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  ///< per vertex, unit; empty: shade with geometric normals
  std::vector<glm::vec2> uvs;      ///< TEXCOORD_0 per vertex; (0, 0) where a primitive has none
  std::vector<std::uint32_t> indices;    ///< 3 per triangle
  std::vector<std::uint32_t> materials;  ///< material index per triangle

  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// A pinhole camera. `aspect` of zero: take the image's.
struct Camera {
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  ///< unit
  glm::vec3 up{0.0f, 1.0f, 0.0f};        ///< unit, orthogonal to forward
  float yfov = 0.8f;                     ///< vertical field of view, radians
  float aspect = 0.0f;
};

struct Scene {
  std::filesystem::path file;
  Mesh mesh;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::optional<Camera> camera;  ///< the first camera of the scene's node hierarchy, if any
};

}  // namespace tracer
