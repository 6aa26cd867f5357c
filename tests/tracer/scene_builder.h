#pragma once
// Scenes built in code for the tracer's tests: quads with UVs, materials, textures.

#include <cstdint>
#include <random>
#include <vector>

#include <lightsampler/backend.h>

#include "tracer/scene.h"

namespace trs_test {

/// The light sampler the tracer's tests use: the CPU backend, on every hardware thread.
inline const lightsampler::SamplerOptions kCpuSampler{.backend = lightsampler::Backend::cpu};

/// Appends the quad p0 p1 p2 p3 (two triangles 0 1 2 and 0 2 3; front face counter-clockwise)
/// with UVs (0,0) (1,0) (1,1) (0,1) at its corners.
inline void add_quad(tracer::Scene& scene, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3,
                     std::uint32_t material) {
  tracer::Mesh& m = scene.mesh;
  const auto base = std::uint32_t(m.positions.size());
  m.positions.insert(m.positions.end(), {p0, p1, p2, p3});
  m.uvs[0].insert(m.uvs[0].end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  m.materials.insert(m.materials.end(), {material, material});
}

inline std::uint32_t add_material(tracer::Scene& scene, const tracer::Material& material) {
  scene.materials.push_back(material);
  return std::uint32_t(scene.materials.size() - 1);
}

/// A diffuse-looking dielectric.
inline tracer::Material matte(glm::vec3 color, float roughness = 1.0f) {
  tracer::Material m;
  m.base_color = color;
  m.metallic = 0.0f;
  m.roughness = roughness;
  return m;
}

/// A texture of random colours, `zero_fraction` of its texels black, nearest lookup, clamped.
inline std::int32_t add_random_texture(tracer::Scene& scene, std::uint32_t width,
                                       std::uint32_t height, double zero_fraction,
                                       std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> value(0.05f, 1.0f);
  std::bernoulli_distribution zero(zero_fraction);
  tracer::Texture t;
  t.name = "random";
  t.width = width;
  t.height = height;
  t.wrap_s = t.wrap_t = tracer::Wrap::clamp;
  t.nearest = true;
  for (std::uint32_t i = 0; i < width * height; ++i)
    t.texels.push_back(zero(rng) ? glm::vec3(0.0f) : glm::vec3(value(rng), value(rng), value(rng)));
  scene.textures.push_back(std::move(t));
  return std::int32_t(scene.textures.size() - 1);
}

/// A 6 x 6 matte floor at y = 0, seen from 3.5 above, looking down: the lighting tests' stage.
inline tracer::Scene floor_seen_from_above() {
  tracer::Scene scene;
  add_quad(scene, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3}, add_material(scene, matte(glm::vec3(0.8f), 0.6f)));
  scene.camera = tracer::Camera{.position = {0, 3.5f, 0}, .forward = {0, -1, 0}, .up = {0, 0, -1}, .yfov = 0.9f};
  return scene;
}

/// A one-sided emissive panel standing on that floor at x = 0, facing +x (counter-clockwise seen
/// from there: the floor at x < 0 sees its back), textured with `texels` x `texels` random
/// colours, `zero_fraction` of them black.
inline void add_standing_panel(tracer::Scene& scene, std::uint32_t texels, double zero_fraction) {
  tracer::Material panel;
  panel.emissive_factor = glm::vec3(2.0f);
  panel.emissive_texture.texture = add_random_texture(scene, texels, texels, zero_fraction, 7);
  add_quad(scene, {0, 0.05f, 1}, {0, 0.05f, -1}, {0, 1.2f, -1}, {0, 1.2f, 1}, add_material(scene, panel));
}

}  // namespace trs_test
