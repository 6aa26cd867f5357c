#include "tracer/path_tracer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "luminance.h"
#include "resampling.h"
#include "surface.h"

namespace tracer {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// A ray leaving `p` along `d`, its origin moved off the surface to the side `d` goes
/// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing
/// Gems, 2019): by a fixed number of float ulps along the geometric normal, which scales with
/// the coordinates' own rounding error; near the origin, where ulps vanish, by a small fixed
/// distance instead.
glm::vec3 offset(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& d) {
  constexpr float kNearOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
  const glm::vec3 n = glm::dot(d, geometric_normal) >= 0.0f ? geometric_normal : -geometric_normal;
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    const auto ulps = std::int32_t(kIntScale * n[i]);
    const std::int32_t bits = std::bit_cast<std::int32_t>(p[i]) + (p[i] < 0.0f ? -ulps : ulps);
    out[i] = std::abs(p[i]) < kNearOrigin ? p[i] + kFloatScale * n[i] : std::bit_cast<float>(bits);
  }
  return out;
}

Ray spawn(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& d) {
  return {offset(p, geometric_normal, d), d};
}

/// Whether the segment between two surface points is blocked, both ends pushed off their
/// surfaces towards each other so that neither surface blocks it.
bool blocked(const Geometry& geometry, const glm::vec3& from, const glm::vec3& from_normal,
             const glm::vec3& to, const glm::vec3& to_normal) {
  const glm::vec3 origin = offset(from, from_normal, to - from);
  const glm::vec3 target = offset(to, to_normal, from - to);
  const glm::vec3 d = target - origin;
  const float length = glm::length(d);
  return length > 0.0f && geometry.occluded({origin, d / length}, length);
}

/// Whether the way from a surface point to a punctual light is blocked: up to the light's
/// position (short of it, so that a fixture the light sits on does not hide it), or without end
/// towards a directional light.
bool blocked_towards(const Geometry& geometry, const glm::vec3& from, const glm::vec3& from_normal,
                     const LightSample& light) {
  if (light.distant) return geometry.occluded(spawn(from, from_normal, light.position), kInfinity);
  const glm::vec3 origin = offset(from, from_normal, light.position - from);
  const glm::vec3 d = light.position - origin;
  const float length = glm::length(d);
  return length > 0.0f && geometry.occluded({origin, d / length}, length * (1.0f - 1e-4f));
}

bool is_black(const glm::vec3& c) { return c.r <= 0.0f && c.g <= 0.0f && c.b <= 0.0f; }

}  // namespace

float solid_angle_density(float area_density, float distance, float cos_at_light) {
  const float c = std::abs(cos_at_light);
  return c > 0.0f ? area_density * distance * distance / c : 0.0f;
}

struct PathTracer::Vertex {
  Hit hit;
  SurfacePoint point;
  glm::vec3 wo;  ///< towards the previous vertex

  /// Where the light strategy sees lights from: the light sample at this vertex and the BSDF
  /// sample's hit from it weigh with the same point.
  ShadingPoint shading_point() const { return {point.position, point.shading_normal}; }
};

PathTracer::PathTracer(const Scene& scene, const Geometry& geometry, const Emitters& emitters,
                       const LightStrategy& strategy, unsigned max_depth)
    : scene_(scene), geometry_(geometry), emitters_(emitters), strategy_(strategy), max_depth_(max_depth) {}

PathEstimate PathTracer::radiance(Ray ray, PathRandom& random, std::uint64_t& rays) const {
  PathEstimate out;
  glm::vec3& sum = out.radiance;
  glm::vec3 throughput(1.0f);
  float bsdf_pdf = 0.0f;  // of the direction that reached this vertex; unused for camera rays
  ShadingPoint previous{};  // the vertex that direction left; unused for camera rays
  for (unsigned depth = 0;; ++depth) {
    const std::optional<Hit> hit = geometry_.intersect(ray, kInfinity);
    ++rays;
    if (!hit) break;
    const Vertex vertex{*hit, surface_point(scene_, *hit), -ray.direction};
    if (depth == 0) out.sees_emitter = emitters_.light_of(hit->triangle).has_value();
    sum += throughput * emitted(vertex, bsdf_pdf, depth == 0 ? nullptr : &previous);
    if (depth == max_depth_) break;

    const Material& material = scene_.materials[vertex.point.material];
    const Bsdf bsdf(surface_params(scene_, material, vertex.point.uv), vertex.point.shading_normal);
    sum += throughput * light_sample(vertex, bsdf, random, rays);

    const auto u = random.floats();
    const std::optional<BsdfSample> s = bsdf.sample(vertex.wo, {u[0], u[1], u[2]});
    if (!s) break;
    // Shading normals can send a direction through the surface; such paths carry nothing.
    const glm::vec3& ng = vertex.point.geometric_normal;
    if (glm::dot(s->wi, ng) * glm::dot(vertex.wo, ng) <= 0.0f) break;
    throughput *= s->weight;
    if (is_black(throughput)) break;
    bsdf_pdf = s->pdf;
    previous = vertex.shading_point();
    ray = spawn(vertex.point.position, ng, s->wi);
  }
  return out;
}

/// Emission seen at a vertex, weighed against the light sample that could have found it from
/// the vertex before (none for a camera ray).
glm::vec3 PathTracer::emitted(const Vertex& vertex, float bsdf_pdf, const ShadingPoint* from) const {
  const std::optional<std::uint32_t> light = emitters_.light_of(vertex.hit.triangle);
  if (!light) return glm::vec3(0.0f);
  const glm::vec3 le = emitters_.radiance(*light, vertex.hit.b1, vertex.hit.b2, vertex.wo);
  if (!from || is_black(le)) return le;
  const float light_pdf = solid_angle_density(
      strategy_.pdf(*light, vertex.hit.b1, vertex.hit.b2, *from), vertex.hit.distance,
      glm::dot(vertex.wo, emitters_.normal(*light)));
  return le * power_heuristic(bsdf_pdf, light_pdf);
}

/// A light sample seen from a shading point: what it would bring if nothing blocked it.
struct PathTracer::Connection {
  LightSample light;
  glm::vec3 wi;
  float distance;
  float cos_light;
  glm::vec3 unshadowed;  ///< f Le / (solid-angle density of the light sample), no MIS weight
};

std::optional<PathTracer::Connection> PathTracer::connect(const Vertex& vertex, const Bsdf& bsdf,
                                                          const LightSample& s) const {
  glm::vec3 wi, le;
  float distance, cos_light = 0.0f, pdf;
  if (s.delta) {  // what the light brings here, and the probability of choosing it
    wi = s.normal;
    distance = s.distant ? kInfinity : glm::length(s.position - vertex.point.position);
    le = s.radiance;
    pdf = s.pdf;
  } else {
    const glm::vec3 to_light = s.position - vertex.point.position;
    distance = glm::length(to_light);
    if (!(distance > 0.0f)) return std::nullopt;
    wi = to_light / distance;
    le = s.radiance_towards(-wi);
    cos_light = glm::dot(-wi, s.normal);
    pdf = solid_angle_density(s.pdf, distance, cos_light);
  }
  if (is_black(le) || !(pdf > 0.0f)) return std::nullopt;
  const glm::vec3& ng = vertex.point.geometric_normal;
  if (glm::dot(wi, ng) * glm::dot(vertex.wo, ng) <= 0.0f) return std::nullopt;
  const glm::vec3 f = bsdf.eval(vertex.wo, wi);
  if (is_black(f)) return std::nullopt;
  return Connection{s, wi, distance, cos_light, f * le / pdf};
}

/// Next-event estimation, weighed against BSDF sampling: a light sample of the strategy, or for
/// `ris` one resampled from its candidates (resampling.h).
///
/// MIS weighs the kept point with the strategy's own density (mis_pdf), the density the BSDF
/// side weighs a hit with (emitted()), so that the two weights sum to one for every path. The
/// resampled density itself has no closed form; it only sharpens the light side's estimate.
glm::vec3 PathTracer::light_sample(const Vertex& vertex, const Bsdf& bsdf, PathRandom& random,
                                   std::uint64_t& rays) const {
  const std::optional<Resampled<Connection>> chosen = resample<Connection>(
      strategy_, random, vertex.shading_point(), [&](const LightSample& s) { return connect(vertex, bsdf, s); });
  if (!chosen) return glm::vec3(0.0f);
  const Connection& kept = chosen->kept;
  const glm::vec3& ng = vertex.point.geometric_normal;
  ++rays;
  const LightSample& light = kept.light;
  if (light.delta ? blocked_towards(geometry_, vertex.point.position, ng, light)
                  : blocked(geometry_, vertex.point.position, ng, light.position, light.normal))
    return glm::vec3(0.0f);
  // No BSDF sample finds a delta light: its sample takes the whole weight.
  const float mis = light.delta ? 1.0f
                                : power_heuristic(solid_angle_density(light.mis_pdf, kept.distance, kept.cos_light),
                                                  bsdf.pdf(vertex.wo, kept.wi));
  return kept.unshadowed * (mis * chosen->scale);
}

}  // namespace tracer
