#include "tracer/emitters.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "emission_maps.h"
#include "surface.h"

namespace tracer {
namespace {

constexpr std::uint32_t kNotLight = std::numeric_limits<std::uint32_t>::max();

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Emitters::Emitters(const Scene& scene, const lightsampler::SamplerOptions& sampler, std::int64_t frame,
                   double seconds)
    : scene_(scene),
      any_coated_(std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.coated(); })),
      punctual_(scene.lights, bounding_radius(scene.mesh.positions)),
      maps_(std::make_unique<EmissionMaps>(scene, frame, seconds)) {
  const auto start = std::chrono::steady_clock::now();
  lights_of_scene_.assign(scene.mesh.triangle_count(), kNotLight);
  reserve(std::size_t(std::count_if(scene.mesh.materials.begin(), scene.mesh.materials.end(),
                                    [&](std::uint32_t m) { return maps_->map_of(m).has_value(); })));
  for (std::uint32_t t = 0; t < scene.mesh.triangle_count(); ++t) {
    if (const std::optional<std::uint32_t> map = maps_->map_of(scene.mesh.materials[t])) add_light(t, *map);
  }
  setup_.emission_ms = ms_since(start);
  if (count() == 0) return;  // punctual lights alone: nothing to sample by texels
  const auto sampler_start = std::chrono::steady_clock::now();
  sampler_ = lightsampler::make_sampler(mesh(), maps_->views(), sampler);
  texels_.emplace(sampler_->maps());
  integrate();  // its first count, in the set-up
  const lightsampler::SamplerSetup sampler_setup = sampler_->setup();
  setup_.sampler_ms = ms_since(sampler_start) - sampler_setup.subdivision_ms;
  setup_.subdivision_ms = sampler_setup.subdivision_ms;
  setup_.sampler_parts = sampler_setup.parts;
}

Emitters::~Emitters() = default;

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


EmissionUpdate Emitters::set_frame(std::int64_t frame, double seconds) {
  EmissionUpdate update;
  update.maps = maps_->set_frame(frame, seconds, update.decode_ms);
  if (!sampler_ || !update.changed()) return update;  // no triangle emits, or nothing changed
  auto start = std::chrono::steady_clock::now();
  for (const std::uint32_t map : update.maps) sampler_->update_map(map, maps_->views()[map]);
  update.upload_ms = ms_since(start);
  start = std::chrono::steady_clock::now();
  integrate();
  update.counting_ms = ms_since(start);
  return update;
}

void Emitters::reserve(std::size_t lights) {
  scene_triangles_.reserve(lights);
  indices_.reserve(3 * lights);
  positions_.reserve(9 * lights);
  uvs_.reserve(6 * lights);
  light_maps_.reserve(lights);
  areas_.reserve(lights);
  normals_.reserve(lights);
}

void Emitters::add_light(std::uint32_t triangle, std::uint32_t map) {
  const Scene& scene = scene_;
  lights_of_scene_[triangle] = count();
  scene_triangles_.push_back(triangle);
  // The light sampler reads the emission where the shader does: through its UV set and transform.
  const TextureRef& mapping = (*maps_)[map].mapping;
  const std::vector<glm::vec2>& uvs = scene.mesh.uvs[mapping.uv_set];
  glm::vec3 p[3];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = scene.mesh.indices[3 * triangle + k];
    p[k] = scene.mesh.positions[v];
    const glm::vec2 uv = uvs.empty() ? glm::vec2(0.0f) : mapping.transform(uvs[v]);
    indices_.push_back(std::uint32_t(positions_.size() / 3));
    positions_.insert(positions_.end(), {p[k].x, p[k].y, p[k].z});
    uvs_.insert(uvs_.end(), {uv.x, uv.y});
  }
  light_maps_.push_back(map);
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
  return emission(light, b1, b2) * coat_transmittance(light, b1, b2, w);
}

float Emitters::coat_transmittance(std::uint32_t light, float b1, float b2, glm::vec3 w) const {
  return any_coated_ ? tracer::coat_transmittance(scene_, scene_triangles_[light], b1, b2, w) : 1.0f;
}

bool Emitters::two_sided(std::uint32_t light) const { return (*maps_)[light_maps_[light]].double_sided; }

double Emitters::power(std::uint32_t light) const { return this->light(light).power(); }

double Emitters::mean_density(std::uint32_t light) const {
  const EmissionMap& e = (*maps_)[light_maps_[light]];
  return e.mean_luminance * e.strength;
}

std::span<const lightsampler::DensityMapView> Emitters::maps() const { return maps_->views(); }

glm::vec3 Emitters::emission(std::uint32_t light, float b1, float b2) const {
  const EmissionMap& e = (*maps_)[light_maps_[light]];
  const std::optional<lightsampler::Texel> texel = texels_->texel(light, b1, b2);
  if (!texel) return glm::vec3(0.0f);
  return e.strength * e.radiance[std::size_t(texel->y) * e.width + texel->x];
}

float Emitters::opacity(std::uint32_t light, float b1, float b2) const {
  return tracer::opacity(scene_, scene_triangles_[light], b1, b2);
}

float Emitters::density(std::uint32_t light, float b1, float b2) const {
  return texels_->density(light, b1, b2);
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
