#pragma once
// What the integrator needs at a ray hit: the point, its normals and UV, and its material with
// textures applied.

#include <cstdint>

#include <glm/glm.hpp>

#include "tracer/bsdf.h"
#include "tracer/geometry.h"
#include "tracer/scene.h"

namespace tracer {

struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 geometric_normal;  ///< unit, front face by counter-clockwise winding
  glm::vec3 shading_normal;    ///< unit, interpolated, on the geometric normal's side
  glm::vec2 uv;
  std::uint32_t material;
};

SurfacePoint surface_point(const Scene& scene, const Hit& hit);

/// The material's parameters at `uv`, textures applied (glTF: factor times texture).
SurfaceParams surface_params(const Scene& scene, const Material& material, glm::vec2 uv);

}  // namespace tracer
