#pragma once
// The scene's emissive triangles as light sources: their emitted radiance, and the density the
// light sampler draws from, which is the luminance of that radiance texel for texel.
//
// Each emissive material becomes one density map: luminance (Rec. 709) of emissive factor times
// emissive texture, with the emissive strength as the map's scale. Emitted radiance is read at
// the texel the sampler names (Sampler::texel), nearest-texel, so that wherever radiance is
// non-zero the density is too, and a light's pdf and its radiance always come from one texel.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <lightsampler/backend.h>

#include "tracer/scene.h"

namespace tracer {

class Emitters {
 public:
  /// Builds the light sampler over the lights with `sampler` (lightsampler::make_sampler).
  /// Throws std::invalid_argument naming the material or texture that cannot be an emitter
  /// (a texture wrap mode the sampler does not have), lightsampler::VulkanUnavailable when a
  /// Vulkan sampler was asked for and none can be made.
  Emitters(const Scene& scene, const lightsampler::SamplerOptions& sampler);
  ~Emitters();

  /// Emissive triangles ("lights"), numbered 0..count()-1 in scene order.
  std::uint32_t count() const { return std::uint32_t(scene_triangles_.size()); }
  /// The light of a scene triangle; none when the triangle does not emit.
  std::optional<std::uint32_t> light_of(std::uint32_t scene_triangle) const;

  /// Radiance leaving a point of a light towards unit direction `w` (linear Rec. 709).
  glm::vec3 radiance(std::uint32_t light, float b1, float b2, glm::vec3 w) const;
  /// Radiance leaving a point of a light towards its front, whatever the direction.
  glm::vec3 emission(std::uint32_t light, float b1, float b2) const;
  /// Whether a light emits from its back face too.
  bool two_sided(std::uint32_t light) const { return emissions_[light_maps_[light]].double_sided; }
  /// Density of the point, luminance of its texel's radiance times strength, as sampled.
  float density(std::uint32_t light, float b1, float b2) const;
  /// The integral of the density over every light (the sampler's N-bar).
  double total_density() const { return total_density_; }
  /// The integral of the density over each light (N-bar_T): its emitted power, in luminance.
  std::span<const double> light_density() const { return light_density_; }
  /// The density a light's emission map has on average over the whole map, whatever part of it
  /// the light's UVs cover: mean texel luminance times strength.
  double mean_density(std::uint32_t light) const { return emissions_[light_maps_[light]].mean_density; }

  glm::vec3 position(std::uint32_t light, float b1, float b2) const;
  /// The light's corners, in the order its barycentrics weigh them (b1: second, b2: third).
  std::array<glm::vec3, 3> vertices(std::uint32_t light) const;
  /// Unit geometric normal, front face by counter-clockwise winding.
  glm::vec3 normal(std::uint32_t light) const { return normals_[light]; }
  float area(std::uint32_t light) const { return areas_[light]; }

  /// The lights as the sampler's inputs (valid while this object lives).
  lightsampler::MeshView mesh() const;
  std::span<const lightsampler::DensityMapView> maps() const { return map_views_; }
  /// The light sampler over the lights: the texel lookups and per-light integrals every
  /// strategy uses, and the point lights of `trs`.
  lightsampler::Sampler& sampler() const { return *sampler_; }

 private:
  /// One emissive material: radiance per texel (emissive factor times texture), its strength.
  struct Emission {
    std::uint32_t width = 1;
    std::uint32_t height = 1;
    std::vector<glm::vec3> radiance;
    std::vector<float> luminance;
    lightsampler::Addressing addressing = lightsampler::Addressing::wrap;
    float strength = 1.0f;
    bool double_sided = false;
    double mean_density = 0.0;  ///< mean of `luminance` times strength
  };
  void add_emission(const Scene& scene, const Material& material);
  void add_light(const Scene& scene, std::uint32_t triangle, std::uint32_t emission);

  std::vector<std::uint32_t> scene_triangles_;
  std::vector<std::uint32_t> lights_of_scene_;  ///< per scene triangle; kNotLight if none
  std::vector<Emission> emissions_;
  std::vector<lightsampler::DensityMapView> map_views_;
  // The lights' mesh in lightsampler's layout.
  std::vector<float> positions_;
  std::vector<float> uvs_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::uint32_t> light_maps_;
  std::vector<glm::vec3> normals_;
  std::vector<float> areas_;
  std::vector<double> light_density_;
  double total_density_ = 0.0;
  std::unique_ptr<lightsampler::Sampler> sampler_;
};

}  // namespace tracer
