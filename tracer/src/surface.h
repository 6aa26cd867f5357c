#pragma once
// What the integrator needs at a ray hit: the point, its normals and UVs, its material with
// textures applied, and how opaque it is there.

#include <cstdint>

#include <glm/glm.hpp>

#include "texture_lookup.h"
#include "tracer/bsdf.h"
#include "tracer/geometry.h"
#include "tracer/scene.h"

namespace tracer {

struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 geometric_normal;  ///< unit, front face by counter-clockwise winding
  /// Unit: interpolated, bent by the material's normal map, and turned to the geometric
  /// normal's side (pbrt-v4's FaceForward).
  glm::vec3 shading_normal;
  SurfaceUvs uv;
  std::uint32_t material;
  /// Unit, on the geometric normal's side: the clearcoat's normal (its own map, or the
  /// interpolated normal); zero where the material has no coat.
  glm::vec3 coat_normal{0.0f};
};

SurfacePoint surface_point(const Scene& scene, const Hit& hit);

/// The UV sets of a point (b1, b2) of a scene triangle.
SurfaceUvs surface_uvs(const Mesh& mesh, std::uint32_t triangle, float b1, float b2);

/// The material's parameters at a point, textures applied (glTF: factor times texture).
SurfaceParams surface_params(const Scene& scene, const Material& material, const SurfacePoint& point);

/// Whether a material may let light straight through somewhere (Bsdf::pass_through): thin and
/// transmissive, and smooth there by its factor or possibly by its roughness texture.
bool may_pass_light_straight(const Material& material);

/// What a clearcoat lets out of the emission under it at a point (b1, b2) of a scene triangle,
/// towards unit `w`: 1 - clearcoat F(|w.n|) (KHR_materials_clearcoat), n the interpolated normal;
/// 1 without a coat.
float coat_transmittance(const Scene& scene, std::uint32_t triangle, float b1, float b2, glm::vec3 w);

/// The probability that a ray stops at a point of the material (its alpha mode: 1 where opaque,
/// 0 or 1 where masked, alpha where blended), the base colour texture read at `uv`, its own
/// (transformed) coordinates.
float opacity_at(const Scene& scene, const Material& material, glm::vec2 uv);
/// The same at a point (b1, b2) of a scene triangle.
float opacity(const Scene& scene, std::uint32_t triangle, float b1, float b2);

}  // namespace tracer
