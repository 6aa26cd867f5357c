#include "tracer/emitters.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>

#include "image_sequence.h"
#include "luminance.h"

namespace tracer {
namespace {


constexpr std::uint32_t kNotLight = std::numeric_limits<std::uint32_t>::max();

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

lightsampler::Addressing addressing(const Texture& texture) {
  if (texture.wrap_s == texture.wrap_t && texture.wrap_s != Wrap::mirrored_repeat)
    return texture.wrap_s == Wrap::repeat ? lightsampler::Addressing::wrap
                                          : lightsampler::Addressing::clamp;
  throw std::invalid_argument(
      "emissive texture " + texture.name +
      ": the light sampler reads repeat or clamp-to-edge, the same on both axes");
}

}  // namespace

Emitters::Emitters(const Scene& scene, const lightsampler::SamplerOptions& sampler, std::int64_t frame,
                   double seconds)
    : scene_(scene), punctual_(scene.lights, bounding_radius(scene.mesh.positions)) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::uint32_t> emission_of_material(scene.materials.size(), kNotLight);
  double decode_ms = 0.0;
  for (std::uint32_t m = 0; m < scene.materials.size(); ++m) {
    if (!scene.materials[m].emissive()) continue;
    emission_of_material[m] = std::uint32_t(emissions_.size());
    emissions_.push_back(emission_at(m, frame, seconds, nullptr, decode_ms));
  }
  lights_of_scene_.assign(scene.mesh.triangle_count(), kNotLight);
  for (std::uint32_t t = 0; t < scene.mesh.triangle_count(); ++t) {
    const std::uint32_t emission = emission_of_material[scene.mesh.materials[t]];
    if (emission != kNotLight) add_light(t, emission);
  }
  for (const Emission& e : emissions_)
    map_views_.push_back({e.luminance, e.width, e.height, e.addressing, e.strength});
  setup_.emission_ms = ms_since(start);
  rebuild_sampler(sampler);
}

Emitters::~Emitters() = default;

void Emitters::rebuild_sampler(const lightsampler::SamplerOptions& sampler) {
  const auto start = std::chrono::steady_clock::now();
  sampler_.reset();  // the old one's memory (a GPU's) before the new one's
  if (count() == 0) return;  // punctual lights alone: nothing to sample by texels
  sampler_ = lightsampler::make_sampler(mesh(), map_views_, sampler);
  integrate();  // its first count, in the set-up (the same integrals after a rebuild)
  const lightsampler::SamplerSetup sampler_setup = sampler_->setup();
  setup_.sampler_ms += ms_since(start) - sampler_setup.subdivision_ms;
  setup_.subdivision_ms = sampler_setup.subdivision_ms;
  setup_.sampler_parts = sampler_setup.parts;
}

void Emitters::integrate() {
  // The counting pass alone gives every light's integral; after update_map it counts the
  // replaced maps' triangles only.
  lightsampler::Frame frame;
  lightsampler::FrameRequest request;
  request.realize = false;
  sampler_->generate(request, frame);
  light_density_.assign(frame.expected_counts.span().begin(), frame.expected_counts.span().end());
  total_density_ = frame.expected_total;
}


Emitters::Emission Emitters::emission_at(std::uint32_t material_index, std::int64_t frame, double seconds,
                                         const Emission* current, double& decode_ms) const {
  const Material& material = scene_.materials[material_index];
  Emission e;
  e.material = material_index;
  e.factor = material.emissive_factor_at(seconds);
  e.strength = material.emissive_strength_at(seconds);
  e.double_sided = material.double_sided;
  if (material.emissive_texture == kNoTexture) {
    e.radiance = {e.factor};
  } else {
    const Texture& texture = scene_.textures.at(std::size_t(material.emissive_texture));
    e.width = texture.width;
    e.height = texture.height;
    e.addressing = addressing(texture);
    e.image_frame = texture.frames ? texture.frames->image_frame(frame) : 0;
    if (current && current->factor == e.factor && current->image_frame == e.image_frame) {
      e.radiance = current->radiance;  // only the strength changes: the texels stay
      e.luminance = current->luminance;
      e.mean_luminance = current->mean_luminance;
      return e;
    }
    const auto start = std::chrono::steady_clock::now();
    const std::vector<glm::vec3> texels = texture.frames ? read_sequence_frame(texture, frame) : texture.texels;
    decode_ms += ms_since(start);
    e.radiance.reserve(texels.size());
    for (const glm::vec3& texel : texels) e.radiance.push_back(glm::max(texel * e.factor, glm::vec3(0.0f)));
  }
  e.luminance.reserve(e.radiance.size());
  double sum = 0.0;
  for (const glm::vec3& radiance : e.radiance) {
    e.luminance.push_back(luminance(radiance));
    sum += e.luminance.back();
  }
  e.mean_luminance = sum / double(e.luminance.size());
  return e;
}

EmissionUpdate Emitters::set_frame(std::int64_t frame, double seconds) {
  EmissionUpdate update;
  for (std::uint32_t i = 0; i < emissions_.size(); ++i) {
    Emission& current = emissions_[i];
    const Material& material = scene_.materials[current.material];
    const bool sequence = material.emissive_texture != kNoTexture &&
                          scene_.textures[std::size_t(material.emissive_texture)].frames;
    if (!sequence && !material.emission_animated()) continue;
    Emission next = emission_at(current.material, frame, seconds, &current, update.decode_ms);
    if (next.factor == current.factor && next.strength == current.strength &&
        next.image_frame == current.image_frame)
      continue;
    current = std::move(next);
    map_views_[i] = {current.luminance, current.width, current.height, current.addressing, current.strength};
    if (!sampler_) continue;  // an emissive material no triangle uses
    const auto start = std::chrono::steady_clock::now();
    sampler_->update_map(i, map_views_[i]);
    update.upload_ms += ms_since(start);
    update.maps.push_back(i);
  }
  if (update.changed()) {
    const auto start = std::chrono::steady_clock::now();
    integrate();
    update.counting_ms = ms_since(start);
  }
  return update;
}

void Emitters::add_light(std::uint32_t triangle, std::uint32_t emission) {
  const Scene& scene = scene_;
  lights_of_scene_[triangle] = count();
  scene_triangles_.push_back(triangle);
  glm::vec3 p[3];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = scene.mesh.indices[3 * triangle + k];
    p[k] = scene.mesh.positions[v];
    const glm::vec2 uv = scene.mesh.uvs.empty() ? glm::vec2(0.0f) : scene.mesh.uvs[v];
    indices_.push_back(std::uint32_t(positions_.size() / 3));
    positions_.insert(positions_.end(), {p[k].x, p[k].y, p[k].z});
    uvs_.insert(uvs_.end(), {uv.x, uv.y});
  }
  light_maps_.push_back(emission);
  const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
  const float length = glm::length(n);
  areas_.push_back(0.5f * length);
  normals_.push_back(length > 0.0f ? n / length : glm::vec3(0.0f));
}

std::optional<std::uint32_t> Emitters::light_of(std::uint32_t scene_triangle) const {
  const std::uint32_t light = lights_of_scene_[scene_triangle];
  if (light == kNotLight) return std::nullopt;
  return light;
}

lightsampler::MeshView Emitters::mesh() const {
  return {positions_, uvs_, indices_, light_maps_};
}

glm::vec3 Emitters::radiance(std::uint32_t light, float b1, float b2, glm::vec3 w) const {
  if (!two_sided(light) && glm::dot(w, normals_[light]) <= 0.0f) return glm::vec3(0.0f);
  return emission(light, b1, b2);
}

glm::vec3 Emitters::emission(std::uint32_t light, float b1, float b2) const {
  const Emission& e = emissions_[light_maps_[light]];
  const std::optional<lightsampler::Texel> texel = sampler_->texel(light, b1, b2);
  if (!texel) return glm::vec3(0.0f);
  return e.strength * e.radiance[std::size_t(texel->y) * e.width + texel->x];
}

float Emitters::density(std::uint32_t light, float b1, float b2) const {
  return sampler_->density(light, b1, b2);
}

glm::vec3 Emitters::position(std::uint32_t light, float b1, float b2) const {
  const auto [p0, p1, p2] = vertices(light);
  return (1.0f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
}

std::array<glm::vec3, 3> Emitters::vertices(std::uint32_t light) const {
  const float* p = &positions_[9 * std::size_t(light)];
  return {glm::vec3(p[0], p[1], p[2]), glm::vec3(p[3], p[4], p[5]), glm::vec3(p[6], p[7], p[8])};
}

}  // namespace tracer
