#pragma once
// The emission of the scene's emissive materials as the light sampler's density maps: each
// emissive material's radiance texel by texel (emissive factor times texture, decoded), its
// luminance (the density), and its strength, as they are at an animation frame; moving to
// another frame decodes only the images that change.

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
  std::uint32_t width = 1;
  std::uint32_t height = 1;
  std::vector<glm::vec3> radiance;
  std::vector<float> luminance;
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
