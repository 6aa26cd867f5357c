#pragma once
// The scene's lights: its emissive triangles, with their emitted radiance and the density the
// light sampler draws from (the luminance of that radiance, texel for texel), and its punctual
// lights.
//
// Each emissive material becomes one density map (emission_maps.h): luminance (Rec. 709) of
// emissive factor times emissive texture, with the emissive strength as the map's scale.
// Emitted radiance is read at the texel the sampler names (Sampler::texel), nearest-texel, so
// that wherever radiance is non-zero the density is too (unless alpha covers the texel
// wholly), and a light's pdf and its radiance always come from one texel.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <lightsampler/backend.h>

#include "tracer/light.h"
#include "tracer/punctual_lights.h"
#include "tracer/scene.h"

namespace tracer {

class EmissionMaps;

/// What a change of frame did to the emission, and what it took.
struct EmissionUpdate {
  std::vector<std::uint32_t> maps;  ///< the emissions (density maps) that changed
  double decode_ms = 0.0;           ///< reading the sequences' new images
  double upload_ms = 0.0;           ///< handing the new maps to the light sampler (to the GPU on Vulkan)
  double counting_ms = 0.0;         ///< counting the changed maps' triangles again
  double strategy_ms = 0.0;         ///< the light strategy's own structures (Renderer::set_frame)

  bool changed() const { return !maps.empty(); }
};

/// What building the emitters took, milliseconds.
struct EmittersSetup {
  double emission_ms = 0.0;      ///< the emission maps: radiance and luminance per texel, the lights' mesh
  double sampler_ms = 0.0;       ///< the light sampler's construction and first count, its subdivision excluded
  double subdivision_ms = 0.0;   ///< the light sampler's subdivision (lightsampler/refinement.h)
  std::uint64_t sampler_parts = 0;  ///< the triangles the light sampler samples (its subdivision's parts)
};

class Emitters {
 public:
  /// Builds the light sampler over the lights with `sampler` (lightsampler::make_sampler), their
  /// emission as it is at animation frame `frame`, `seconds` into the animation (Scene: image
  /// sequences and keyed factors). The scene must outlive the emitters.
  /// Throws std::invalid_argument naming the material or texture that cannot be an emitter
  /// (a texture wrap mode the sampler does not have), lightsampler::VulkanUnavailable when a
  /// Vulkan sampler was asked for and none can be made, trs::FileError for a sequence's image
  /// that cannot be read.
  Emitters(const Scene& scene, const lightsampler::SamplerOptions& sampler, std::int64_t frame = 0,
           double seconds = 0.0);
  ~Emitters();

  /// The emission of animation frame `frame`, `seconds` into the animation: the maps that
  /// change are replaced in the light sampler, which counts their triangles again, and the
  /// lights' integrals follow. Throws trs::FileError for an image that cannot be read.
  EmissionUpdate set_frame(std::int64_t frame, double seconds);

  /// Emissive triangles ("lights"), numbered 0..count()-1 in scene order.
  std::uint32_t count() const { return std::uint32_t(scene_triangles_.size()); }
  /// The light of a scene triangle; none when the triangle does not emit.
  std::optional<std::uint32_t> light_of(std::uint32_t scene_triangle) const;

  /// Radiance leaving a point of a light towards unit direction `w` (linear Rec. 709), through
  /// its material's clearcoat, if any (coat_transmittance()).
  glm::vec3 radiance(std::uint32_t light, float b1, float b2, glm::vec3 w) const;
  /// The share of a point's emission that its clearcoat lets out towards unit `w`: 1 uncoated.
  float coat_transmittance(std::uint32_t light, float b1, float b2, glm::vec3 w) const;
  /// Radiance leaving a point of a light towards its front, whatever the direction, where a
  /// ray stops on it.
  glm::vec3 emission(std::uint32_t light, float b1, float b2) const;
  /// The probability that a ray stops at a point of a light (its material's alpha: 0 on a hole,
  /// alpha where blended, else 1). What a light sample brings is its emission times this, the
  /// emission a ray meets on average.
  float opacity(std::uint32_t light, float b1, float b2) const;
  /// Whether a light emits from its back face too.
  bool two_sided(std::uint32_t light) const;
  /// Density of the point, luminance of its texel's radiance times strength, as sampled.
  float density(std::uint32_t light, float b1, float b2) const;
  /// The integral of the density over every light (the sampler's N-bar).
  double total_density() const { return total_density_; }
  /// The integral of the density over each light (N-bar_T): the luminance it emits from one face
  /// per unit projected solid angle.
  std::span<const double> light_density() const { return light_density_; }
  /// Light `light`, numbered as the light choices number them: an emissive triangle (below
  /// count()), then punctual light `light - count()`.
  Light light(std::uint32_t light) const { return Light(*this, light); }
  /// light(light).power(): its emitted power, W in luminance.
  double power(std::uint32_t light) const;
  /// The density a light's emission map has on average over the whole map, whatever part of it
  /// the light's UVs cover: mean texel luminance times strength.
  double mean_density(std::uint32_t light) const;

  glm::vec3 position(std::uint32_t light, float b1, float b2) const;
  /// The light's corners, in the order its barycentrics weigh them (b1: second, b2: third).
  std::array<glm::vec3, 3> vertices(std::uint32_t light) const;
  /// Unit geometric normal, front face by counter-clockwise winding.
  glm::vec3 normal(std::uint32_t light) const { return normals_[light]; }
  float area(std::uint32_t light) const { return areas_[light]; }

  /// The lights as the sampler's inputs (valid while this object lives).
  lightsampler::MeshView mesh() const;
  std::span<const lightsampler::DensityMapView> maps() const;
  /// The scene's punctual lights, sampled beside the emissive triangles.
  const PunctualLights& punctual() const { return punctual_; }

  /// The light sampler over the lights: the texel lookups and per-light integrals every
  /// strategy reads. None where no triangle emits.
  const lightsampler::Sampler& sampler() const { return *sampler_; }
  /// The same, to draw point lights with (`trs`, `auto`'s measure).
  lightsampler::Sampler& sampler() { return *sampler_; }
  const EmittersSetup& setup() const { return setup_; }

 private:
  /// Room for `lights` in the lights' arrays: millions of them would otherwise be copied as
  /// the arrays grow.
  void reserve(std::size_t lights);
  void add_light(std::uint32_t triangle, std::uint32_t map);
  /// The lights' integrals, from the sampler's counting pass.
  void integrate();

  const Scene& scene_;
  bool any_coated_ = false;  ///< whether any material has a clearcoat (which dims emission under it)
  PunctualLights punctual_;
  std::vector<std::uint32_t> scene_triangles_;
  std::vector<std::uint32_t> lights_of_scene_;  ///< per scene triangle; kNotLight if none
  std::unique_ptr<EmissionMaps> maps_;  ///< the emission, decoded
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
  /// The sampler's maps, asked once: connections read a texel or a density at every point.
  std::optional<lightsampler::MapQueries> texels_;
  EmittersSetup setup_;
};

}  // namespace tracer
