#include "gltf_materials.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <regex>
#include <string>
#include <utility>

#include "image_sequence.h"
#include "scene_io/file_error.h"
#include "scene_io/image_output.h"
#include "texture_decode.h"

namespace tracer {
namespace {

using trs::gltf::Document;

/// Colour is sRGB-encoded in integer images; data textures hold their values as they are. A base
/// colour whose alpha covers the surface keeps its image's alpha too, and so do data textures
/// read in their alpha channel (KHR_materials_specular's, KHR_materials_sheen's roughness).
enum class Use { colour, colour_and_alpha, data, data_and_alpha };

bool is_colour(Use use) { return use == Use::colour || use == Use::colour_and_alpha; }

std::string label(const char* kind, std::size_t index, const std::string& name) {
  return std::string(kind) + " " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
}

Wrap wrap_mode(int mode, const Document& document, const std::string& what) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT:
      return Wrap::repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return Wrap::clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return Wrap::mirrored_repeat;
    default:
      document.fail(what + ": unknown wrap mode " + std::to_string(mode));
  }
}

/// The image of glTF texture `index`, decoded to linear RGB for `use`, with its sampler's modes.
Texture read_texture(const Document& document, int index, Use use) {
  const tinygltf::Model& model = document.model();
  const std::string what = "texture " + std::to_string(index);
  if (index < 0 || std::size_t(index) >= model.textures.size())
    document.fail(what + " does not exist");
  const tinygltf::Texture& source = model.textures[std::size_t(index)];
  if (source.source < 0 || std::size_t(source.source) >= model.images.size()) {
    document.fail(what +
                  " has no image in a format glTF defines (extensions such as "
                  "KHR_texture_basisu are not supported)");
  }
  const tinygltf::Image& image = model.images[std::size_t(source.source)];

  // Problems are the image file's where it has one, else the document's about this image.
  Texture texture;
  const trs::Alpha alpha = use == Use::colour_and_alpha || use == Use::data_and_alpha ? trs::Alpha::keep : trs::Alpha::drop;
  std::filesystem::path file = document.file();
  std::string prefix;
  trs::Image pixels;
  if (!image.uri.empty()) {
    file = document.resolve_uri(image.uri);
    texture.name = image.uri;
    pixels = trs::read_image(file, alpha);
  } else {
    const std::string name = label("image", std::size_t(source.source), image.name);
    texture.name = image.name.empty() ? name : image.name;
    const std::string format = image.mimeType.substr(image.mimeType.find('/') + 1);
    pixels = trs::read_image(image.image, format, file, name, alpha);
    prefix = name + ": ";
  }
  texture.width = pixels.width;
  texture.height = pixels.height;
  texture.alpha = std::move(pixels.alpha);
  texture.texels = linear_texels(std::move(pixels), is_colour(use), file, prefix);
  // An image that plays a sequence: its frames are read as its poster is (colour).
  const tinygltf::Value& frames = image.extras.Get("frames");
  if (is_colour(use) && frames.IsString()) {
    texture.frames = read_image_sequence(document.file(), frames.Get<std::string>(), texture.width,
                                         texture.height, label("image", std::size_t(source.source), image.name));
  }

  if (source.sampler >= 0) {
    if (std::size_t(source.sampler) >= model.samplers.size())
      document.fail(what + ": sampler " + std::to_string(source.sampler) + " does not exist");
    const tinygltf::Sampler& sampler = model.samplers[std::size_t(source.sampler)];
    texture.wrap_s = wrap_mode(sampler.wrapS, document, what);
    texture.wrap_t = wrap_mode(sampler.wrapT, document, what);
    texture.nearest = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  }
  return texture;
}

/// A finite number of a JSON object, or `fallback` where it is absent.
double number(const tinygltf::Value& object, const char* key, double fallback, const Document& document,
              const std::string& what) {
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsNumber()) return fallback;
  const double number = value.GetNumberAsDouble();
  if (!std::isfinite(number)) document.fail(what + ": " + key + " is not finite");
  return number;
}

/// A pair of finite numbers of a JSON object, or `fallback` where it is absent.
glm::vec2 pair(const tinygltf::Value& object, const char* key, glm::vec2 fallback, const Document& document,
               const std::string& what) {
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsArray()) return fallback;
  if (value.ArrayLen() != 2 || !value.Get(0).IsNumber() || !value.Get(1).IsNumber())
    document.fail(what + ": " + key + " must be two numbers");
  const glm::dvec2 pair(value.Get(0).GetNumberAsDouble(), value.Get(1).GetNumberAsDouble());
  if (!std::isfinite(pair.x) || !std::isfinite(pair.y)) document.fail(what + ": " + key + " is not finite");
  return glm::vec2(pair);
}

/// A texture reference's UV set and transform: its texCoord, which KHR_texture_transform may
/// override, and that extension's offset, rotation (counter-clockwise, radians) and scale,
/// applied as the ratified extension defines: scale, then rotate, then offset.
void read_mapping(int tex_coord, const tinygltf::ExtensionMap& extensions, TextureRef& ref,
                  const Document& document, const std::string& what) {
  const auto transform = extensions.find("KHR_texture_transform");
  if (transform != extensions.end()) {
    const tinygltf::Value& t = transform->second;
    const std::string where = what + " KHR_texture_transform";
    tex_coord = int(number(t, "texCoord", tex_coord, document, where));
    const glm::vec2 scale = pair(t, "scale", glm::vec2(1.0f), document, where);
    const auto rotation = float(number(t, "rotation", 0.0, document, where));
    const float c = std::cos(rotation), s = std::sin(rotation);
    // Columns: u' = c sx u + s sy v, v' = -s sx u + c sy v.
    ref.transform.linear = glm::mat2(c * scale.x, -s * scale.x, s * scale.y, c * scale.y);
    ref.transform.offset = pair(t, "offset", glm::vec2(0.0f), document, where);
  }
  if (tex_coord < 0 || std::size_t(tex_coord) >= kUvSets) {
    document.fail(what + " uses TEXCOORD_" + std::to_string(tex_coord) +
                  "; only TEXCOORD_0 and TEXCOORD_1 are supported");
  }
  ref.uv_set = std::uint32_t(tex_coord);
}

/// Scene textures by glTF texture and use, each decoded once however many materials share it.
class Textures {
 public:
  Textures(const Document& document, std::vector<Texture>& textures, double& decode_seconds)
      : document_(document), textures_(textures), decode_seconds_(decode_seconds) {}

  /// A material's texture reference (tinygltf's TextureInfo or NormalTextureInfo).
  template <class Info>
  TextureRef get(const Info& info, Use use, const std::string& what) {
    TextureRef ref;
    if (info.index < 0) return ref;
    read_mapping(info.texCoord, info.extensions, ref, document_, what);
    const auto [entry, added] = loaded_.try_emplace({info.index, use}, kNoTexture);
    if (added) {
      const auto start = std::chrono::steady_clock::now();
      textures_.push_back(read_texture(document_, info.index, use));
      decode_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      entry->second = static_cast<std::int32_t>(textures_.size() - 1);
    }
    ref.texture = entry->second;
    return ref;
  }

 private:
  const Document& document_;
  std::vector<Texture>& textures_;
  double& decode_seconds_;
  std::map<std::pair<int, Use>, std::int32_t> loaded_;
};

glm::vec3 rgb(const std::vector<double>& factor, const Document& document,
              const std::string& what) {
  if (factor.size() < 3) document.fail(what + " has fewer than 3 components");
  return {float(factor[0]), float(factor[1]), float(factor[2])};
}

/// glTF's alphaMode and alphaCutoff.
void read_alpha(const tinygltf::Material& source, Material& material, const Document& document,
                const std::string& what) {
  if (source.alphaMode == "MASK") {
    material.alpha_mode = AlphaMode::mask;
  } else if (source.alphaMode == "BLEND") {
    material.alpha_mode = AlphaMode::blend;
  } else if (source.alphaMode != "OPAQUE") {
    document.fail(what + ": unknown alphaMode '" + source.alphaMode + "'");
  }
  material.alpha_cutoff = float(source.alphaCutoff);
  if (!(material.alpha_cutoff >= 0.0f) || !std::isfinite(material.alpha_cutoff))
    document.fail(what + ": alphaCutoff must be finite and non-negative");
}

float emissive_strength(const tinygltf::Material& material, const Document& document,
                        const std::string& what) {
  const auto extension = material.extensions.find("KHR_materials_emissive_strength");
  if (extension == material.extensions.end()) return 1.0f;
  const tinygltf::Value& strength = extension->second.Get("emissiveStrength");
  if (!strength.IsNumber()) return 1.0f;  // the extension's default
  const double value = strength.GetNumberAsDouble();
  if (!(value >= 0.0) || !std::isfinite(value))
    document.fail(what + ": emissiveStrength must be finite and non-negative");
  return float(value);
}

/// The keyframes of an animation sampler: times (seconds, increasing) and `components` values
/// per time, finite and non-negative.
Keyframes keyframes(const Document& document, const trs::gltf::Document::PointerChannel& channel,
                    int components) {
  const tinygltf::AnimationSampler& sampler =
      document.model().animations[std::size_t(channel.animation)].samplers[std::size_t(channel.sampler)];
  const std::string what = "animation " + std::to_string(channel.animation) + " sampler " +
                           std::to_string(channel.sampler) + " (" + channel.pointer + ")";
  if (sampler.interpolation != "LINEAR" && sampler.interpolation != "STEP")
    document.fail(what + ": " + sampler.interpolation + " interpolation is not supported (LINEAR and STEP are)");
  Keyframes keys;
  keys.step = sampler.interpolation == "STEP";
  keys.times = document.floats(sampler.input, 1, what + " input");
  const std::vector<float> values = document.floats(sampler.output, components, what + " output");
  if (keys.times.empty() || values.size() != keys.times.size() * std::size_t(components))
    document.fail(what + ": needs one output per input time, and at least one");
  for (std::size_t i = 0; i < keys.times.size(); ++i) {
    if (!std::isfinite(keys.times[i]) || (i > 0 && !(keys.times[i] > keys.times[i - 1])))
      document.fail(what + ": input times must be finite and increasing");
    glm::vec3 value(0.0f);
    for (int k = 0; k < components; ++k) value[k] = values[i * std::size_t(components) + std::size_t(k)];
    if (!(value.x >= 0.0f && value.y >= 0.0f && value.z >= 0.0f) || !std::isfinite(value.x + value.y + value.z))
      document.fail(what + ": output values must be finite and non-negative");
    keys.values.push_back(value);
  }
  return keys;
}

/// The emission that animation channels drive by pointer (KHR_animation_pointer): a material's
/// emissiveFactor or its KHR_materials_emissive_strength. Other pointers animate what the
/// renderer keeps still.
void read_emission_animation(const Document& document, Scene& scene) {
  static const std::regex pointer(
      "/materials/([0-9]+)/(emissiveFactor|extensions/KHR_materials_emissive_strength/emissiveStrength)");
  for (const auto& channel : document.pointer_channels()) {
    std::smatch match;
    if (!std::regex_match(channel.pointer, match, pointer)) continue;
    const std::size_t m = std::stoul(match[1].str());
    if (m >= scene.materials.size())
      document.fail("animation " + std::to_string(channel.animation) + ": " + channel.pointer +
                    " names a material that does not exist");
    Material& material = scene.materials[m];
    if (match[2] == "emissiveFactor")
      material.emissive_factor_keys = keyframes(document, channel, 3);
    else
      material.emissive_strength_keys = keyframes(document, channel, 1);
  }
}

/// A material extension's textureInfo (or normalTextureInfo) as tinygltf reads the core's.
struct ExtensionTexture {
  int index = -1;
  int texCoord = 0;
  double scale = 1.0;  ///< a normal texture's
  tinygltf::ExtensionMap extensions;
};

ExtensionTexture extension_texture(const tinygltf::Value& object, const char* key, const Document& document,
                                   const std::string& what) {
  ExtensionTexture info;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsObject()) return info;
  const std::string where = what + " " + key;
  const tinygltf::Value& index = value.Get("index");
  if (!index.IsNumber() || !(index.GetNumberAsDouble() >= 0.0)) document.fail(where + ": index must be a texture");
  info.index = int(index.GetNumberAsDouble());
  info.texCoord = int(number(value, "texCoord", 0.0, document, where));
  info.scale = number(value, "scale", 1.0, document, where);
  const tinygltf::Value& extensions = value.Get("extensions");
  if (extensions.IsObject()) {
    for (const std::string& name : extensions.Keys()) info.extensions[name] = extensions.Get(name);
  }
  return info;
}

/// A number of an extension's object, default `fallback`, that must lie in [low, high].
float ranged(const tinygltf::Value& object, const char* key, double fallback, double low, double high,
             const Document& document, const std::string& what) {
  const double value = number(object, key, fallback, document, what);
  if (!(value >= low && value <= high)) {
    document.fail(what + ": " + key + " " + std::to_string(value) + " is out of its range [" + std::to_string(low) +
                  ", " + (std::isinf(high) ? std::string("inf") : std::to_string(high)) + "]");
  }
  return float(value);
}

/// Three numbers of an extension's object in [0, high] each, default `fallback`.
glm::vec3 ranged_colour(const tinygltf::Value& object, const char* key, glm::vec3 fallback, double high,
                        const Document& document, const std::string& what) {
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsArray()) return fallback;
  if (value.ArrayLen() != 3) document.fail(what + ": " + key + " must be three numbers");
  glm::vec3 colour;
  for (int c = 0; c < 3; ++c) {
    const tinygltf::Value& component = value.Get(c);
    const double v = component.IsNumber() ? component.GetNumberAsDouble() : -1.0;
    if (!(v >= 0.0 && v <= high)) document.fail(what + ": " + key + " must be three numbers in [0, " + std::to_string(high) + "]");
    colour[c] = float(v);
  }
  return colour;
}

/// The material extensions that change how the surface scatters light, each as its specification
/// defines its properties and their defaults; a value out of range is refused, naming it.
class ExtensionReader {
 public:
  ExtensionReader(const tinygltf::Material& source, Textures& textures, const Document& document,
                  const std::string& what)
      : source_(source), textures_(textures), document_(document), what_(what) {}

  void read(Material& material) {
    if (const tinygltf::Value* e = find("KHR_materials_specular")) {
      material.specular.factor = ranged(*e, "specularFactor", 1.0, 0.0, 1.0, document_, where_);
      material.specular.texture = texture(*e, "specularTexture", Use::data_and_alpha);
      material.specular_color.factor = ranged_colour(*e, "specularColorFactor", glm::vec3(1.0f), kInfinity, document_, where_);
      material.specular_color.texture = texture(*e, "specularColorTexture", Use::colour);
    }
    if (const tinygltf::Value* e = find("KHR_materials_ior")) {
      material.ior = float(number(*e, "ior", 1.5, document_, where_));
      if (!(material.ior >= 1.0f || material.ior == 0.0f))
        document_.fail(where_ + ": ior " + std::to_string(material.ior) + " must be at least 1, or 0");
    }
    if (const tinygltf::Value* e = find("KHR_materials_transmission")) {
      material.transmission.factor = ranged(*e, "transmissionFactor", 0.0, 0.0, 1.0, document_, where_);
      material.transmission.texture = texture(*e, "transmissionTexture", Use::data);
    }
    if (const tinygltf::Value* e = find("KHR_materials_volume")) {
      // A ray tracer measures the distances a thickness texture approximates; the factor alone
      // says whether the surface bounds a volume.
      if (ranged(*e, "thicknessFactor", 0.0, 0.0, kInfinity, document_, where_) > 0.0f) {
        Volume volume;
        volume.attenuation_distance = ranged(*e, "attenuationDistance", kInfinity, 0.0, kInfinity, document_, where_);
        if (!(volume.attenuation_distance > 0.0f)) document_.fail(where_ + ": attenuationDistance must be positive");
        volume.attenuation_color = ranged_colour(*e, "attenuationColor", glm::vec3(1.0f), 1.0, document_, where_);
        material.volume = volume;
      }
    }
    if (const tinygltf::Value* e = find("KHR_materials_clearcoat")) {
      material.clearcoat.factor = ranged(*e, "clearcoatFactor", 0.0, 0.0, 1.0, document_, where_);
      material.clearcoat.texture = texture(*e, "clearcoatTexture", Use::data);
      material.clearcoat_roughness.factor = ranged(*e, "clearcoatRoughnessFactor", 0.0, 0.0, 1.0, document_, where_);
      material.clearcoat_roughness.texture = texture(*e, "clearcoatRoughnessTexture", Use::data);
      const ExtensionTexture normal = extension_texture(*e, "clearcoatNormalTexture", document_, where_);
      material.clearcoat_normal_texture = textures_.get(normal, Use::data, where_ + " clearcoatNormalTexture");
      material.clearcoat_normal_scale = float(normal.scale);
    }
    if (const tinygltf::Value* e = find("KHR_materials_sheen")) {
      material.sheen_color.factor = ranged_colour(*e, "sheenColorFactor", glm::vec3(0.0f), 1.0, document_, where_);
      material.sheen_color.texture = texture(*e, "sheenColorTexture", Use::colour);
      material.sheen_roughness.factor = ranged(*e, "sheenRoughnessFactor", 0.0, 0.0, 1.0, document_, where_);
      material.sheen_roughness.texture = texture(*e, "sheenRoughnessTexture", Use::data_and_alpha);
    }
  }

 private:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  /// The extension's object, `where_` naming it for messages; none where the material lacks it.
  const tinygltf::Value* find(const char* name) {
    const auto found = source_.extensions.find(name);
    if (found == source_.extensions.end()) return nullptr;
    where_ = what_ + " " + name;
    if (!found->second.IsObject()) document_.fail(where_ + " must be an object");
    return &found->second;
  }

  TextureRef texture(const tinygltf::Value& object, const char* key, Use use) {
    return textures_.get(extension_texture(object, key, document_, where_), use, where_ + " " + key);
  }

  const tinygltf::Material& source_;
  Textures& textures_;
  const Document& document_;
  const std::string& what_;
  std::string where_;
};

}  // namespace

void read_materials(const Document& document, Scene& scene) {
  Textures textures(document, scene.textures, scene.texture_decode_seconds);
  const auto& materials = document.model().materials;
  for (std::size_t m = 0; m < materials.size(); ++m) {
    const tinygltf::Material& source = materials[m];
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    const std::string what = label("material", m, source.name);
    Material material;
    material.name = source.name;
    material.base_color = rgb(pbr.baseColorFactor, document, what + " baseColorFactor");
    if (pbr.baseColorFactor.size() == 4) material.alpha = float(pbr.baseColorFactor[3]);
    read_alpha(source, material, document, what);
    material.base_color_texture =
        textures.get(pbr.baseColorTexture, material.alpha_tested() ? Use::colour_and_alpha : Use::colour,
                     what + " baseColorTexture");
    material.metallic = float(pbr.metallicFactor);
    material.roughness = float(pbr.roughnessFactor);
    material.metallic_roughness_texture =
        textures.get(pbr.metallicRoughnessTexture, Use::data, what + " metallicRoughnessTexture");
    material.normal_texture = textures.get(source.normalTexture, Use::data, what + " normalTexture");
    material.normal_scale = float(source.normalTexture.scale);
    material.emissive_factor = rgb(source.emissiveFactor, document, what + " emissiveFactor");
    material.emissive_texture =
        textures.get(source.emissiveTexture, Use::colour, what + " emissiveTexture");
    material.emissive_strength = emissive_strength(source, document, what);
    material.double_sided = source.doubleSided;
    ExtensionReader(source, textures, document, what).read(material);
    scene.materials.push_back(std::move(material));
  }
  read_emission_animation(document, scene);
}

}  // namespace tracer
