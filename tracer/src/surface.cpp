#include "surface.h"

#include "microfacet.h"

#include <algorithm>
#include <cmath>

namespace tracer {
namespace {

template <class T>
T interpolate(const std::vector<T>& values, const std::uint32_t* v, float b1, float b2) {
  return (1.0f - b1 - b2) * values[v[0]] + b1 * values[v[1]] + b2 * values[v[2]];
}

/// The unit tangent and bitangent of the normal map's +X and +Y at a point of shading normal
/// `n`: the file's tangents, else the directions in which the map's u grows and its v falls
/// (glTF's v runs down the image, +Y up it), from the triangle's positions and UVs. Both are
/// made orthogonal to `n`; none where the UVs are degenerate or absent.
std::optional<std::array<glm::vec3, 2>> tangent_frame(const Scene& scene, const TextureRef& map,
                                                      const std::uint32_t* v, float b1, float b2,
                                                      glm::vec3 n) {
  const Mesh& mesh = scene.mesh;
  glm::vec3 t(0.0f), b_hint(0.0f);
  float sign = 1.0f;
  if (!mesh.tangents.empty() && mesh.tangents[v[0]].w != 0.0f) {
    t = glm::vec3(interpolate(mesh.tangents, v, b1, b2));
    sign = mesh.tangents[v[0]].w;
  } else {
    const glm::vec3 p0 = mesh.positions[v[0]];
    const glm::vec3 dp1 = mesh.positions[v[1]] - p0, dp2 = mesh.positions[v[2]] - p0;
    const std::vector<glm::vec2>& uvs = mesh.uvs[map.uv_set];
    if (uvs.empty()) return std::nullopt;  // a set no primitive has: every UV (0, 0)
    const glm::vec2 uv0 = map.transform(uvs[v[0]]);
    const glm::vec2 du1 = map.transform(uvs[v[1]]) - uv0, du2 = map.transform(uvs[v[2]]) - uv0;
    const float det = du1.x * du2.y - du1.y * du2.x;
    if (!(std::abs(det) > 0.0f)) return std::nullopt;
    t = (dp1 * du2.y - dp2 * du1.y) / det;        // dp/du
    b_hint = (dp1 * du2.x - dp2 * du1.x) / det;   // -dp/dv
  }
  t -= glm::dot(t, n) * n;
  const float length = glm::length(t);
  if (!(length > 0.0f)) return std::nullopt;
  t /= length;
  glm::vec3 b = glm::cross(n, t);
  if (b_hint != glm::vec3(0.0f)) sign = glm::dot(b, b_hint) < 0.0f ? -1.0f : 1.0f;
  return std::array{t, sign < 0.0f ? -b : b};
}

/// The normal `n` bent by a normal map (glTF: tangent-space RGB in [0, 1] for [-1, 1], X and Y
/// scaled by the map's scale).
glm::vec3 mapped_normal(const Scene& scene, const TextureRef& map, float scale, const std::uint32_t* v,
                        const Hit& hit, const SurfaceUvs& uv, glm::vec3 n) {
  const auto frame = tangent_frame(scene, map, v, hit.b1, hit.b2, n);
  if (!frame) return n;
  const glm::vec3 texel = lookup(scene.textures[std::size_t(map.texture)], texture_uv(map, uv));
  const glm::vec3 local = 2.0f * texel - 1.0f;
  const glm::vec3 bent = scale * (local.x * (*frame)[0] + local.y * (*frame)[1]) + local.z * n;
  const float length = glm::length(bent);
  return length > 0.0f ? bent / length : n;
}

/// `n` turned to the side of the geometric normal `ng` (pbrt-v4's FaceForward).
glm::vec3 face_forward(glm::vec3 n, glm::vec3 ng) { return glm::dot(n, ng) < 0.0f ? -n : n; }

float value(const Scene& scene, const ScalarInput& input, const SurfaceUvs& uv) {
  if (!input.texture.present()) return input.factor;
  const Texture& texture = scene.textures[std::size_t(input.texture.texture)];
  const glm::vec2 at = texture_uv(input.texture, uv);
  const float channel = input.channel == ScalarInput::Channel::alpha ? lookup_alpha(texture, at)
                                                                      : lookup(texture, at)[int(input.channel)];
  return input.factor * channel;
}

glm::vec3 value(const Scene& scene, const ColourInput& input, const SurfaceUvs& uv) {
  if (!input.texture.present()) return input.factor;
  return input.factor * lookup(scene.textures[std::size_t(input.texture.texture)], texture_uv(input.texture, uv));
}

}  // namespace

SurfaceUvs surface_uvs(const Mesh& mesh, std::uint32_t triangle, float b1, float b2) {
  const std::uint32_t* v = &mesh.indices[3 * std::size_t(triangle)];
  SurfaceUvs uv{};
  for (std::size_t set = 0; set < kUvSets; ++set)
    if (!mesh.uvs[set].empty()) uv[set] = interpolate(mesh.uvs[set], v, b1, b2);
  return uv;
}

SurfacePoint surface_point(const Scene& scene, const Hit& hit) {
  const Mesh& mesh = scene.mesh;
  const std::uint32_t* v = &mesh.indices[3 * std::size_t(hit.triangle)];
  const glm::vec3 p0 = mesh.positions[v[0]], p1 = mesh.positions[v[1]], p2 = mesh.positions[v[2]];

  SurfacePoint s;
  s.position = interpolate(mesh.positions, v, hit.b1, hit.b2);
  const glm::vec3 cross = glm::cross(p1 - p0, p2 - p0);
  const float area2 = glm::length(cross);
  // Embree can report a hit on a sliver whose normal underflows; any unit vector will do there.
  s.geometric_normal = area2 > 0.0f ? cross / area2 : glm::vec3(0.0f, 0.0f, 1.0f);
  s.shading_normal = s.geometric_normal;
  if (!mesh.normals.empty()) {
    const glm::vec3 n = interpolate(mesh.normals, v, hit.b1, hit.b2);
    const float length = glm::length(n);
    if (length > 0.0f) s.shading_normal = n / length;
  }
  s.uv = surface_uvs(mesh, hit.triangle, hit.b1, hit.b2);
  s.material = mesh.materials[hit.triangle];
  const Material& material = scene.materials[s.material];
  // The coat has a normal map of its own, or none: the interpolated normal, not the base's map.
  if (material.coated()) {
    s.coat_normal = material.clearcoat_normal_texture.present()
                        ? mapped_normal(scene, material.clearcoat_normal_texture, material.clearcoat_normal_scale, v,
                                        hit, s.uv, s.shading_normal)
                        : s.shading_normal;
    s.coat_normal = face_forward(s.coat_normal, s.geometric_normal);
  }
  if (material.normal_texture.present())
    s.shading_normal = mapped_normal(scene, material.normal_texture, material.normal_scale, v, hit, s.uv, s.shading_normal);
  s.shading_normal = face_forward(s.shading_normal, s.geometric_normal);
  return s;
}

SurfaceParams surface_params(const Scene& scene, const Material& material, const SurfacePoint& point) {
  const SurfaceUvs& uv = point.uv;
  SurfaceParams params{material.base_color, material.metallic, material.roughness};
  params.specular = value(scene, material.specular, uv);
  params.specular_color = value(scene, material.specular_color, uv);
  params.ior = material.ior;
  params.transmission = value(scene, material.transmission, uv);
  params.thin_walled = !material.volume;
  if (material.coated()) {
    params.clearcoat = value(scene, material.clearcoat, uv);
    params.clearcoat_roughness = value(scene, material.clearcoat_roughness, uv);
    params.clearcoat_normal = point.coat_normal;
  }
  params.sheen_color = value(scene, material.sheen_color, uv);
  params.sheen_roughness = value(scene, material.sheen_roughness, uv);
  const TextureRef& base = material.base_color_texture;
  if (base.present()) params.base_color *= lookup(scene.textures[std::size_t(base.texture)], texture_uv(base, uv));
  const TextureRef& mr_map = material.metallic_roughness_texture;
  if (mr_map.present()) {
    const glm::vec3 mr = lookup(scene.textures[std::size_t(mr_map.texture)], texture_uv(mr_map, uv));
    params.roughness *= mr.g;
    params.metallic *= mr.b;
  }
  return params;
}

float coat_transmittance(const Scene& scene, std::uint32_t triangle, float b1, float b2, glm::vec3 w) {
  const Mesh& mesh = scene.mesh;
  const Material& material = scene.materials[mesh.materials[triangle]];
  if (!material.coated()) return 1.0f;
  const std::uint32_t* v = &mesh.indices[3 * std::size_t(triangle)];
  glm::vec3 n = glm::cross(mesh.positions[v[1]] - mesh.positions[v[0]], mesh.positions[v[2]] - mesh.positions[v[0]]);
  if (!mesh.normals.empty()) n = interpolate(mesh.normals, v, b1, b2);
  const float length = glm::length(n);
  const float mu = length > 0.0f ? std::abs(glm::dot(w, n)) / length : 1.0f;
  return 1.0f - value(scene, material.clearcoat, surface_uvs(mesh, triangle, b1, b2)) * schlick(0.04f, 1.0f, mu);
}

bool may_pass_light_straight(const Material& material) {
  if (!material.transmissive() || material.volume) return false;
  return material.roughness * material.roughness < kMinAlpha || material.metallic_roughness_texture.present();
}

float opacity_at(const Scene& scene, const Material& material, glm::vec2 uv) {
  if (!material.alpha_tested()) return 1.0f;
  float alpha = material.alpha;
  const TextureRef& base = material.base_color_texture;
  if (base.present()) alpha *= lookup_alpha(scene.textures[std::size_t(base.texture)], uv);
  if (material.alpha_mode == AlphaMode::mask) return alpha >= material.alpha_cutoff ? 1.0f : 0.0f;
  return std::clamp(alpha, 0.0f, 1.0f);
}

float opacity(const Scene& scene, std::uint32_t triangle, float b1, float b2) {
  const Material& material = scene.materials[scene.mesh.materials[triangle]];
  if (!material.alpha_tested()) return 1.0f;
  return opacity_at(scene, material, texture_uv(material.base_color_texture, surface_uvs(scene.mesh, triangle, b1, b2)));
}

}  // namespace tracer
