#pragma once
// The emission of the scene's emissive materials as the light sampler's density maps: each
// emissive material's radiance texel by texel (emissive factor times texture, decoded), its
// density (the luminance, times the share of the texel that the material's alpha leaves), and
// its strength, as they are at an animation frame; moving to another frame decodes only the
// images that change.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <lightsampler/backend.h>

#include "tracer/scene.h"

namespace tracer {

/// One emissive material: radiance per texel (emissive factor times texture), its strength.
struct EmissionMap {
  std::uint32_t material = 0;
  /// Whose texture coordinates the lights carry to the light sampler: the emissive texture's;
  /// for an emissive factor alone on a surface whose alpha comes from the base colour
  /// texture, the base colour's, so that the map can follow the alpha; else TEXCOORD_0.
  TextureRef mapping;
  std::uint32_t width = 1;
  std::uint32_t height = 1;
  std::vector<glm::vec3> radiance;
  /// Per texel, the share of it where a ray stops on the surface (surface.h, opacity_at): mean
  /// over a 4 x 4 grid of points in the texel. Empty where that is 1 throughout, and where the
  /// alpha is read through other texture coordinates than the emission (then the density
  /// ignores the alpha, and MIS alone keeps light samples on holes from biasing the image).
  std::vector<float> coverage;
  std::vector<float> luminance;  ///< the density: luminance of the radiance, times the coverage
  lightsampler::Addressing addressing = lightsampler::Addressing::wrap;
  float strength = 1.0f;
  bool double_sided = false;
  double mean_luminance = 0.0;  ///< mean of `luminance`, the strength not applied
  // What the emission shows now, to tell a change of frame that changes it.
  glm::vec3 factor{0.0f};
  std::int64_t image_frame = 0;  ///< of the texture's sequence
};

class EmissionMaps {
 public:
  /// Every emissive material's map at animation frame `frame`, `seconds` into the animation.
  /// The scene must outlive the maps. Throws std::invalid_argument naming a texture the light
  /// sampler cannot address, trs::FileError for a sequence's image that cannot be read.
  EmissionMaps(const Scene& scene, std::int64_t frame, double seconds);

  std::uint32_t size() const { return std::uint32_t(maps_.size()); }
  const EmissionMap& operator[](std::uint32_t map) const { return maps_[map]; }
  /// The map of material `material`; none where it does not emit.
  std::optional<std::uint32_t> map_of(std::uint32_t material) const;
  /// The maps as the light sampler reads them (valid while this object lives).
  std::span<const lightsampler::DensityMapView> views() const { return views_; }

  /// Moves to animation frame `frame`: the maps whose emission changes are replaced, their
  /// images decoded (timed into `decode_ms`). Returns the maps that changed.
  std::vector<std::uint32_t> set_frame(std::int64_t frame, double seconds, double& decode_ms);

 private:
  /// Material `material`'s map at a frame and time, its texels decoded only where they differ
  /// from `current`'s.
  EmissionMap map_at(std::uint32_t material, std::int64_t frame, double seconds, const EmissionMap* current,
                     double& decode_ms) const;

  const Scene& scene_;
  std::vector<EmissionMap> maps_;
  std::vector<std::uint32_t> map_of_material_;  ///< per material; kNoMap if it does not emit
  std::vector<lightsampler::DensityMapView> views_;
};

}  // namespace tracer
