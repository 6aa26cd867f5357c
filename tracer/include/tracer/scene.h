#pragma once
// A scene as the tracer renders it: one world-space triangle mesh, its materials and textures
// (linear, decoded at load time), its punctual lights, and a camera. Loaders fill it; nothing here knows glTF.

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene_io/frame_pattern.h"

namespace tracer {

/// How texture coordinates outside [0, 1] are brought back, per axis (glTF sampler wrap modes).
enum class Wrap : std::uint8_t { repeat, clamp, mirrored_repeat };

/// Images that make a texture change over time: image f is the texture at animation frame f,
/// and before the first image and after the last those hold.
struct ImageSequence {
  std::filesystem::path directory;
  trs::FramePattern names;  ///< the images' file names: "screen.%04d.png"
  std::int64_t first = 0;   ///< every frame from first to last has its file
  std::int64_t last = 0;

  /// The frame whose image stands at animation frame `frame`: held beyond the ends.
  std::int64_t image_frame(std::int64_t frame) const { return std::clamp(frame, first, last); }
  /// The file of image frame `frame` (not clamped).
  std::filesystem::path file(std::int64_t frame) const { return directory / names.format(frame); }
};

/// Linear RGB texels, row-major, row 0 at v = 0 (glTF's convention: the image's top row).
/// Colour textures are decoded from their encoding (sRGB) to linear Rec.709 at load time; data
/// textures (metallic-roughness) keep their values.
struct Texture {
  std::string name;  ///< for messages: the image's URI or name
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec3> texels;  ///< width * height
  /// Base colour textures whose image has an alpha channel: width * height values in [0, 1].
  /// Empty otherwise (alpha 1).
  std::vector<float> alpha;
  Wrap wrap_s = Wrap::repeat;
  Wrap wrap_t = Wrap::repeat;
  /// glTF's magnification filter asked for nearest. Emission is always read nearest (texel for
  /// texel with the light sampler); other textures are bilinear unless this is set.
  bool nearest = false;
  /// An emissive texture that plays a sequence; `texels` are then its poster image's. Every
  /// image of the sequence has the poster's size.
  std::optional<ImageSequence> frames;
};

/// A value keyed over time (a glTF animation sampler), read between keys LINEAR or STEP; before
/// the first key and after the last, those hold.
struct Keyframes {
  std::vector<float> times;       ///< seconds, increasing
  std::vector<glm::vec3> values;  ///< one per time; a scalar is in x
  bool step = false;

  glm::vec3 at(double seconds) const;
};

inline constexpr std::int32_t kNoTexture = -1;
/// TEXCOORD_0 and TEXCOORD_1: the UV sets a texture can read.
inline constexpr std::size_t kUvSets = 2;

/// An affine map of texture coordinates (KHR_texture_transform): uv' = linear uv + offset.
struct UvTransform {
  glm::mat2 linear{1.0f};
  glm::vec2 offset{0.0f};

  glm::vec2 operator()(glm::vec2 uv) const { return linear * uv + offset; }
  bool operator==(const UvTransform&) const = default;
};

/// Where a material reads a texture: which one, through which UV set and transform.
struct TextureRef {
  std::int32_t texture = kNoTexture;
  std::uint32_t uv_set = 0;  ///< below kUvSets
  UvTransform transform;

  bool present() const { return texture != kNoTexture; }
  /// Whether two references put a surface point at the same texture coordinates.
  bool same_mapping(const TextureRef& other) const {
    return uv_set == other.uv_set && transform == other.transform;
  }
};

/// How a material's alpha (base colour factor times texture) covers its surface (glTF alphaMode).
enum class AlphaMode : std::uint8_t {
  opaque,  ///< alpha is ignored
  mask,    ///< the surface is there where alpha >= alpha_cutoff, a hole elsewhere
  blend,   ///< a ray stops with probability alpha (stochastic transparency, as Cycles and pbrt-v4)
};

/// A scalar input of a material extension: its factor times, where it has one, one channel of a
/// texture (glTF's rule for every factor and texture pair).
struct ScalarInput {
  enum class Channel : std::uint8_t { r, g, b, alpha };
  float factor = 0.0f;
  TextureRef texture;
  Channel channel = Channel::r;
};

/// A colour input of a material extension: its factor times, where it has one, a colour texture
/// (sRGB-encoded, decoded to linear).
struct ColourInput {
  glm::vec3 factor{0.0f};
  TextureRef texture;
};

/// KHR_materials_volume: the medium a closed mesh of non-zero thickness encloses, which absorbs
/// by Beer-Lambert: transmittance attenuation_color^(distance / attenuation_distance).
struct Volume {
  glm::vec3 attenuation_color{1.0f};
  float attenuation_distance = std::numeric_limits<float>::infinity();

  /// The transmittance over `distance` through the medium.
  glm::vec3 transmittance(float distance) const;
};

/// glTF's metallic-roughness material and the material extensions the renderer implements
/// (SurfaceParams says what each does). Texture channels as glTF defines them: base colour RGB
/// and alpha; roughness in G, metallic in B of the metallic-roughness texture; the tangent-space
/// normal in RGB of the normal texture; the extensions' as each input says.
struct Material {
  std::string name;
  glm::vec3 base_color{1.0f};
  float alpha = 1.0f;  ///< the base colour factor's alpha
  TextureRef base_color_texture;
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;
  float metallic = 1.0f;
  float roughness = 1.0f;
  TextureRef metallic_roughness_texture;
  TextureRef normal_texture;
  float normal_scale = 1.0f;  ///< scales the tangent-space normal's X and Y
  // KHR_materials_specular, _ior, _transmission, _volume (absent: thin-walled), _clearcoat and
  // _sheen, with their defaults.
  ScalarInput specular{1.0f, {}, ScalarInput::Channel::alpha};
  ColourInput specular_color{glm::vec3(1.0f), {}};
  float ior = 1.5f;
  ScalarInput transmission{0.0f, {}, ScalarInput::Channel::r};
  std::optional<Volume> volume;
  ScalarInput clearcoat{0.0f, {}, ScalarInput::Channel::r};
  ScalarInput clearcoat_roughness{0.0f, {}, ScalarInput::Channel::g};
  TextureRef clearcoat_normal_texture;  ///< none: the coat is not normal-mapped, even where the base is
  float clearcoat_normal_scale = 1.0f;
  ColourInput sheen_color{glm::vec3(0.0f), {}};
  ScalarInput sheen_roughness{0.0f, {}, ScalarInput::Channel::alpha};
  /// Emitted radiance = emissive_factor * emissive texture * emissive_strength
  /// (KHR_materials_emissive_strength), in linear Rec.709.
  glm::vec3 emissive_factor{0.0f};
  TextureRef emissive_texture;
  float emissive_strength = 1.0f;
  /// Single-sided surfaces emit from their front face only (counter-clockwise winding).
  bool double_sided = false;
  /// The factor and the strength animated (KHR_animation_pointer): then they replace the
  /// constants above, which hold at rest.
  std::optional<Keyframes> emissive_factor_keys;
  std::optional<Keyframes> emissive_strength_keys;  ///< in x

  /// The emissive factor and strength at a time.
  glm::vec3 emissive_factor_at(double seconds) const {
    return emissive_factor_keys ? emissive_factor_keys->at(seconds) : emissive_factor;
  }
  float emissive_strength_at(double seconds) const {
    return emissive_strength_keys ? emissive_strength_keys->at(seconds).x : emissive_strength;
  }

  /// Whether the material emits at any time.
  bool emissive() const;
  /// Whether its emission changes over time (its texture's sequence aside).
  bool emission_animated() const { return emissive_factor_keys || emissive_strength_keys; }
  /// Whether alpha can cut or thin the surface anywhere.
  bool alpha_tested() const { return alpha_mode != AlphaMode::opaque; }
  /// Whether light can go through the surface somewhere (KHR_materials_transmission).
  bool transmissive() const { return transmission.factor > 0.0f && metallic < 1.0f; }
  /// Whether a clearcoat covers any of it (which dims its emission).
  bool coated() const { return clearcoat.factor > 0.0f; }
};

/// Every triangle of the scene in world space. Vertices are not shared between primitives.
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  ///< per vertex, unit; empty: shade with geometric normals
  /// TEXCOORD_0 and TEXCOORD_1 per vertex; (0, 0) where a primitive has none. A set no
  /// primitive has is empty.
  std::array<std::vector<glm::vec2>, kUvSets> uvs;
  /// Per vertex where the file gives them (glTF's TANGENT: unit xyz in world space, w the
  /// bitangent's sign); empty where no normal-mapped primitive has them: normal maps then take
  /// their tangents from the UVs (surface.h).
  std::vector<glm::vec4> tangents;
  std::vector<std::uint32_t> indices;    ///< 3 per triangle
  std::vector<std::uint32_t> materials;  ///< material index per triangle

  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// A light without area (glTF's KHR_lights_punctual), in the renderer's radiometric units: the
/// file's candela and lux over 683 lm/W, as Blender's glTF importer converts them
/// (docs/renderer.md, "Punctual lights").
struct PunctualLight {
  enum class Kind : std::uint8_t { point, spot, directional };
  Kind kind = Kind::point;
  std::string name;  ///< for messages and reports: "light 2 'Sun'"
  glm::vec3 position{0.0f};                  ///< point and spot
  glm::vec3 direction{0.0f, 0.0f, -1.0f};    ///< spot and directional: unit, the way the light travels
  /// Point and spot: radiant intensity, W/sr, along the spot's axis. Directional: irradiance on
  /// a surface facing it, W/m^2. Linear Rec.709.
  glm::vec3 intensity{0.0f};
  float cos_inner = 1.0f;  ///< spot: full intensity inside this cone
  float cos_outer = 0.0f;  ///< spot: none outside this one
  float range = 0.0f;      ///< point and spot: 0 where the file gives none (no cut-off)
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
  std::vector<PunctualLight> lights;  ///< in the order of the nodes that place them
  std::optional<Camera> camera;  ///< the first camera of the scene's node hierarchy, if any
  /// What loading took, for reports: in all, and of that decoding the texture images.
  double load_seconds = 0.0;
  double texture_decode_seconds = 0.0;

  /// Whether any emission changes over time: a sequence or keyed factors.
  bool animated() const;
};

}  // namespace tracer
