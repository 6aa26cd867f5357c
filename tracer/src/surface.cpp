#include "surface.h"

#include "texture_lookup.h"

namespace tracer {

SurfacePoint surface_point(const Scene& scene, const Hit& hit) {
  const Mesh& mesh = scene.mesh;
  const std::uint32_t* v = &mesh.indices[3 * std::size_t(hit.triangle)];
  const float b0 = 1.0f - hit.b1 - hit.b2;
  const glm::vec3 p0 = mesh.positions[v[0]], p1 = mesh.positions[v[1]], p2 = mesh.positions[v[2]];

  SurfacePoint s;
  s.position = b0 * p0 + hit.b1 * p1 + hit.b2 * p2;
  const glm::vec3 cross = glm::cross(p1 - p0, p2 - p0);
  const float area2 = glm::length(cross);
  // Embree can report a hit on a sliver whose normal underflows; any unit vector will do there.
  s.geometric_normal = area2 > 0.0f ? cross / area2 : glm::vec3(0.0f, 0.0f, 1.0f);
  s.shading_normal = s.geometric_normal;
  if (!mesh.normals.empty()) {
    const glm::vec3 n = b0 * mesh.normals[v[0]] + hit.b1 * mesh.normals[v[1]] +
                        hit.b2 * mesh.normals[v[2]];
    const float length = glm::length(n);
    if (length > 0.0f) {
      s.shading_normal = n / length;
      if (glm::dot(s.shading_normal, s.geometric_normal) < 0.0f) s.shading_normal = -s.shading_normal;
    }
  }
  s.uv = mesh.uvs.empty() ? glm::vec2(0.0f)
                          : b0 * mesh.uvs[v[0]] + hit.b1 * mesh.uvs[v[1]] + hit.b2 * mesh.uvs[v[2]];
  s.material = mesh.materials[hit.triangle];
  return s;
}

SurfaceParams surface_params(const Scene& scene, const Material& material, glm::vec2 uv) {
  SurfaceParams params{material.base_color, material.metallic, material.roughness, material.specular};
  if (material.base_color_texture != kNoTexture)
    params.base_color *= lookup(scene.textures[std::size_t(material.base_color_texture)], uv);
  if (material.metallic_roughness_texture != kNoTexture) {
    const glm::vec3 mr = lookup(scene.textures[std::size_t(material.metallic_roughness_texture)], uv);
    params.roughness *= mr.g;
    params.metallic *= mr.b;
  }
  return params;
}

}  // namespace tracer
