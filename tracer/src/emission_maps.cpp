#include "emission_maps.h"

#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>

#include "image_sequence.h"
#include "luminance.h"
#include "surface.h"

namespace tracer {
namespace {

constexpr std::uint32_t kNoMap = std::numeric_limits<std::uint32_t>::max();

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// See EmissionMap::mapping.
TextureRef emission_mapping(const Scene& scene, const Material& material) {
  if (material.emissive_texture.present()) return material.emissive_texture;
  const TextureRef& base = material.base_color_texture;
  if (material.alpha_tested() && base.present() && !scene.textures[std::size_t(base.texture)].alpha.empty())
    return base;
  return {};
}

/// See EmissionMap::coverage.
std::vector<float> coverage(const Scene& scene, const Material& material, const EmissionMap& e) {
  if (!material.alpha_tested() || !material.base_color_texture.same_mapping(e.mapping)) return {};
  const TextureRef& base = material.base_color_texture;
  if (!base.present() || scene.textures[std::size_t(base.texture)].alpha.empty())  // the factor's alpha alone
    return std::vector<float>(std::size_t(e.width) * e.height, opacity_at(scene, material, glm::vec2(0.0f)));
  constexpr int kGrid = 4;
  std::vector<float> share(std::size_t(e.width) * e.height);
  for (std::uint32_t y = 0; y < e.height; ++y) {
    for (std::uint32_t x = 0; x < e.width; ++x) {
      float sum = 0.0f;
      for (int j = 0; j < kGrid; ++j) {
        for (int i = 0; i < kGrid; ++i) {
          const glm::vec2 uv((float(x) + (float(i) + 0.5f) / kGrid) / float(e.width),
                             (float(y) + (float(j) + 0.5f) / kGrid) / float(e.height));
          sum += opacity_at(scene, material, uv);
        }
      }
      share[std::size_t(y) * e.width + x] = sum / (kGrid * kGrid);
    }
  }
  return share;
}

lightsampler::Addressing addressing(const Texture& texture) {
  if (texture.wrap_s != texture.wrap_t)
    throw std::invalid_argument("emissive texture " + texture.name +
                                ": the light sampler reads one wrap mode on both axes");
  switch (texture.wrap_s) {
    case Wrap::repeat: return lightsampler::Addressing::wrap;
    case Wrap::clamp: return lightsampler::Addressing::clamp;
    case Wrap::mirrored_repeat: return lightsampler::Addressing::mirror;
  }
  throw std::invalid_argument("emissive texture " + texture.name + ": unknown wrap mode");
}

lightsampler::DensityMapView view_of(const EmissionMap& m) {
  return {m.luminance, m.width, m.height, m.addressing, m.strength};
}

}  // namespace

EmissionMaps::EmissionMaps(const Scene& scene, std::int64_t frame, double seconds)
    : scene_(scene), map_of_material_(scene.materials.size(), kNoMap) {
  double decode_ms = 0.0;  // part of the emission's set-up
  for (std::uint32_t m = 0; m < scene.materials.size(); ++m) {
    if (!scene.materials[m].emissive()) continue;
    map_of_material_[m] = std::uint32_t(maps_.size());
    maps_.push_back(map_at(m, frame, seconds, nullptr, decode_ms));
  }
  for (const EmissionMap& m : maps_) views_.push_back(view_of(m));
}

std::optional<std::uint32_t> EmissionMaps::map_of(std::uint32_t material) const {
  const std::uint32_t map = map_of_material_[material];
  if (map == kNoMap) return std::nullopt;
  return map;
}

EmissionMap EmissionMaps::map_at(std::uint32_t material_index, std::int64_t frame, double seconds,
                                 const EmissionMap* current, double& decode_ms) const {
  const Material& material = scene_.materials[material_index];
  EmissionMap e;
  e.material = material_index;
  e.factor = material.emissive_factor_at(seconds);
  e.strength = material.emissive_strength_at(seconds);
  e.double_sided = material.double_sided;
  e.mapping = emission_mapping(scene_, material);
  if (!e.mapping.present()) {
    e.radiance = {e.factor};
  } else {
    const Texture& texture = scene_.textures.at(std::size_t(e.mapping.texture));
    e.width = texture.width;
    e.height = texture.height;
    e.addressing = addressing(texture);
    e.image_frame = texture.frames ? texture.frames->image_frame(frame) : 0;
    if (current && current->factor == e.factor && current->image_frame == e.image_frame) {
      e.radiance = current->radiance;  // only the strength changes: the texels stay
      e.coverage = current->coverage;
      e.luminance = current->luminance;
      e.mean_luminance = current->mean_luminance;
      return e;
    }
    if (!material.emissive_texture.present()) {  // the factor over the alpha's texels
      e.radiance.assign(texture.texels.size(), glm::max(e.factor, glm::vec3(0.0f)));
    } else {
      const auto start = std::chrono::steady_clock::now();
      const std::vector<glm::vec3> texels = texture.frames ? read_sequence_frame(texture, frame) : texture.texels;
      decode_ms += ms_since(start);
      e.radiance.reserve(texels.size());
      for (const glm::vec3& texel : texels) e.radiance.push_back(glm::max(texel * e.factor, glm::vec3(0.0f)));
    }
  }
  e.coverage = current ? current->coverage : coverage(scene_, material, e);
  e.luminance.reserve(e.radiance.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < e.radiance.size(); ++i) {
    e.luminance.push_back(luminance(e.radiance[i]) * (e.coverage.empty() ? 1.0f : e.coverage[i]));
    sum += e.luminance.back();
  }
  e.mean_luminance = sum / double(e.luminance.size());
  return e;
}

std::vector<std::uint32_t> EmissionMaps::set_frame(std::int64_t frame, double seconds, double& decode_ms) {
  std::vector<std::uint32_t> changed;
  for (std::uint32_t i = 0; i < maps_.size(); ++i) {
    EmissionMap& current = maps_[i];
    const Material& material = scene_.materials[current.material];
    const bool sequence = material.emissive_texture.present() &&
                          scene_.textures[std::size_t(material.emissive_texture.texture)].frames;
    if (!sequence && !material.emission_animated()) continue;
    EmissionMap next = map_at(current.material, frame, seconds, &current, decode_ms);
    if (next.factor == current.factor && next.strength == current.strength &&
        next.image_frame == current.image_frame)
      continue;
    current = std::move(next);
    views_[i] = view_of(current);
    changed.push_back(i);
  }
  return changed;
}

}  // namespace tracer
