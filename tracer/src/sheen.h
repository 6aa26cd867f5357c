#pragma once
// The sheen lobe of KHR_materials_sheen: Conty and Kulla's "Charlie" microfiber distribution and
// its fitted visibility (Conty and Kulla 2017, "Production Friendly Microfacet Sheen BRDF"), in a
// local frame whose +z is the normal, as the extension's implementation notes give them.

#include <glm/glm.hpp>

namespace tracer {

/// Sheen of roughness `roughness` (the extension's sheenRoughness; alpha = roughness^2).
struct Sheen {
  float alpha;

  explicit Sheen(float roughness);
  /// D G / (4 |wo.z| |wi.z|) times |wi.z| for wo and wi on the same side: the lobe's f |cos| for
  /// a white sheen colour.
  float reflection(glm::vec3 wo, glm::vec3 wi) const;
};

}  // namespace tracer
