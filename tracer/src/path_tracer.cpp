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

/// The smooth thin surfaces a shadow ray crosses, one behind the other, before it counts as
/// blocked; a path passes through as many without scattering (PathTracer::radiance).
constexpr unsigned kMaxCrossings = 64;

bool is_black(const glm::vec3& c) { return c.r <= 0.0f && c.g <= 0.0f && c.b <= 0.0f; }

/// Whether a ray leaving a surface point along `wi` goes through its material's medium: into the
/// back of a volume's boundary. Media do not nest: a ray that leaves any other surface is in none.
const Volume* medium_along(const Material& material, const glm::vec3& geometric_normal, const glm::vec3& wi) {
  return material.volume && glm::dot(wi, geometric_normal) < 0.0f ? &*material.volume : nullptr;
}

/// Whether `wi` and `wo` are on the sides of the surface that the shading normal says: the same
/// for a reflection, opposite for a transmission. Shading normals can send a direction through the
/// geometric surface (or keep one from crossing it); such directions carry nothing.
bool consistent_sides(const glm::vec3& geometric_normal, const glm::vec3& shading_normal, const glm::vec3& wo,
                      const glm::vec3& wi) {
  const float geometric = glm::dot(wi, geometric_normal) * glm::dot(wo, geometric_normal);
  const float shading = glm::dot(wi, shading_normal) * glm::dot(wo, shading_normal);
  return geometric != 0.0f && (geometric > 0.0f) == (shading > 0.0f);
}

bool consistent_sides(const SurfacePoint& point, const glm::vec3& wo, const glm::vec3& wi) {
  return consistent_sides(point.geometric_normal, point.shading_normal, wo, wi);
}

}  // namespace

struct PathTracer::Vertex {
  Hit hit;
  SurfacePoint point;
  glm::vec3 wo;  ///< towards the previous vertex

  /// Where the light strategy sees lights from: the light sample at this vertex and the BSDF
  /// sample's hit from it weigh with the same point.
  ShadingPoint shading_point() const { return {point.position, point.shading_normal}; }
};

/// A light sample seen from a shading point: what it would bring if nothing blocked it.
struct PathTracer::Connection {
  LightLiSample light;
  glm::vec3 unshadowed;  ///< f Li / (solid-angle density of the light sample), no MIS weight
};

PathTracer::PathTracer(const Scene& scene, const Geometry& geometry, const Emitters& emitters,
                       const LightStrategy& strategy, unsigned max_depth)
    : scene_(scene), geometry_(geometry), emitters_(emitters), strategy_(strategy), max_depth_(max_depth) {
  for (const Material& m : scene.materials) pass_through_materials_.push_back(may_pass_light_straight(m));
  any_pass_through_ = std::find(pass_through_materials_.begin(), pass_through_materials_.end(), true) !=
                      pass_through_materials_.end();
}

PathEstimate PathTracer::radiance(Ray ray, PathRandom& random, std::uint64_t& rays, const FirstSurface* first) const {
  PathEstimate out;
  glm::vec3& sum = out.radiance;
  glm::vec3 throughput(1.0f);
  // Of the direction that left the last scattering vertex, times the probabilities of the
  // pass-throughs since: the density with which BSDF sampling found what this ray meets. Unused
  // for camera rays.
  float bsdf_pdf = 0.0f;
  ShadingPoint previous{};  // the last scattering vertex; unused for camera rays
  float travelled = 0.0f;   // from it to the ray's origin, through pass-throughs
  const Volume* medium = nullptr;
  unsigned crossings = 0;
  for (unsigned depth = 0;;) {
    const bool camera_ray = depth == 0 && crossings == 0;
    std::optional<Hit> hit;
    if (first && camera_ray) {
      hit = first->hit;
    } else {
      hit = geometry_.intersect(ray, kInfinity);
      ++rays;
    }
    if (!hit) break;
    if (medium) throughput *= medium->transmittance(hit->distance);
    const Vertex vertex{*hit, surface_point(scene_, *hit), -ray.direction};
    const float distance = travelled + hit->distance;
    if (depth == 0 && emitters_.light_of(hit->triangle)) out.sees_emitter = true;
    const glm::vec3 le = throughput * emitted(vertex, bsdf_pdf, depth == 0 ? nullptr : &previous, distance);
    sum += le;
    if (depth == 0) out.seen_emission += le;

    const Material& material = scene_.materials[vertex.point.material];
    const bool may_pass = pass_through_materials_[vertex.point.material] && crossings < kMaxCrossings;
    if (depth == max_depth_ && !may_pass) break;
    const Bsdf bsdf(surface_params(scene_, material, vertex.point), vertex.point.shading_normal);
    std::optional<BsdfSample> s;
    if (depth < max_depth_) {
      if (first && camera_ray) {
        if (first->light)
          if (const std::optional<Connection> c = connect(vertex, bsdf, *first->light))
            sum += throughput * shade(vertex, bsdf, *c, 1.0f, rays);
      } else {
        sum += throughput * light_sample(vertex, bsdf, random, rays);
        ++out.light_queries;
      }
      const auto u = random.floats();
      s = bsdf.sample(vertex.wo, {u[0], u[1], u[2]});
    } else if (const std::optional<PassThrough> through = bsdf.pass_through(vertex.wo)) {
      // No more scattering, but what lies behind a pane is still found as it would be below the
      // last depth, so that the light samples that crossed the pane keep their MIS partner.
      if (random.floats()[0] < through->probability)
        s = BsdfSample{-vertex.wo, through->transmittance / through->probability, through->probability, true};
    }
    if (!s) break;
    throughput *= s->weight;
    if (is_black(throughput)) break;
    const glm::vec3& ng = vertex.point.geometric_normal;
    if (s->pass_through) {
      // Straight on, as if the surface were not there: the path's last scattering vertex, its
      // direction's density (times this draw's probability), and its medium stay.
      ++crossings;
      bsdf_pdf *= s->pdf;
      travelled = distance;
      ray = spawn(vertex.point.position, ng, ray.direction);
      continue;
    }
    if (!consistent_sides(vertex.point, vertex.wo, s->wi)) break;
    bsdf_pdf = s->pdf;
    previous = vertex.shading_point();
    travelled = 0.0f;
    medium = medium_along(material, ng, s->wi);
    ray = spawn(vertex.point.position, ng, s->wi);
    ++depth;
  }
  return out;
}

/// Emission seen at a vertex `distance` from the last scattering vertex, weighed against the
/// light sample that could have found it from there (none for a camera ray).
glm::vec3 PathTracer::emitted(const Vertex& vertex, float bsdf_pdf, const ShadingPoint* from, float distance) const {
  const std::optional<std::uint32_t> light = emitters_.light_of(vertex.hit.triangle);
  if (!light) return glm::vec3(0.0f);
  const glm::vec3 le = emitters_.radiance(*light, vertex.hit.b1, vertex.hit.b2, vertex.wo);
  if (!from || is_black(le)) return le;
  const float light_pdf =
      emitters_.light(*light).pdf_li(strategy_.pdf(*light, vertex.hit.b1, vertex.hit.b2, *from), vertex.wo, distance);
  return le * power_heuristic(bsdf_pdf, light_pdf);
}

/// What reaches the end of a shadow ray: every smooth thin surface on the way lets its
/// straight-through transmittance pass (Bsdf::pass_through), anything else blocks it.
struct PathTracer::Visibility {
  glm::vec3 transmittance{1.0f};
  float probability = 1.0f;  ///< of BSDF sampling passing through those surfaces, for MIS
};

std::optional<PathTracer::Visibility> PathTracer::visibility(glm::vec3 origin, glm::vec3 direction, float length,
                                                            std::uint64_t& rays) const {
  ++rays;
  if (!any_pass_through_) {
    if (geometry_.occluded({origin, direction}, length)) return std::nullopt;
    return Visibility{};
  }
  Visibility seen;
  const bool endless = std::isinf(length);  // towards a directional light
  const glm::vec3 end = endless ? origin : origin + length * direction;
  for (unsigned crossed = 0;; ++crossed) {
    const std::optional<Hit> hit = geometry_.intersect({origin, direction}, length);
    if (!hit) return seen;
    const std::uint32_t m = scene_.mesh.materials[hit->triangle];
    if (!pass_through_materials_[m] || crossed == kMaxCrossings) return std::nullopt;
    const SurfacePoint point = surface_point(scene_, *hit);
    const std::optional<PassThrough> through =
        Bsdf(surface_params(scene_, scene_.materials[m], point), point.shading_normal).pass_through(-direction);
    if (!through) return std::nullopt;
    seen.transmittance *= through->transmittance;
    seen.probability *= through->probability;
    if (is_black(seen.transmittance)) return std::nullopt;
    origin = offset(point.position, point.geometric_normal, direction);
    if (!endless) length = glm::dot(end - origin, direction);
    ++rays;
    if (!(length > 0.0f)) return seen;
  }
}

std::optional<PathTracer::Connection> PathTracer::connect(const Vertex& vertex, const Bsdf& bsdf,
                                                          const LightLiSample& s) const {
  if (is_black(s.li) || !(s.pdf > 0.0f)) return std::nullopt;
  if (!consistent_sides(vertex.point, vertex.wo, s.wi)) return std::nullopt;
  const glm::vec3 f = bsdf.eval(vertex.wo, s.wi);
  if (is_black(f)) return std::nullopt;
  return Connection{s, f * s.li / s.pdf};
}

/// Next-event estimation, weighed against BSDF sampling: a light sample of the strategy, or for
/// `ris` one resampled from its candidates (resampling.h). The shadow ray crosses smooth thin
/// surfaces (visibility()).
///
/// MIS weighs the kept point with the strategy's own density (mis_pdf), the density the BSDF
/// side weighs a hit with (emitted()), so that the two weights sum to one for every path. The
/// resampled density itself has no closed form; it only sharpens the light side's estimate. Where
/// the shadow ray crossed surfaces, the BSDF side reaches the light only by passing through each:
/// its density carries their probabilities, on both sides alike.
glm::vec3 PathTracer::light_sample(const Vertex& vertex, const Bsdf& bsdf, PathRandom& random,
                                   std::uint64_t& rays) const {
  const std::optional<Resampled<Connection>> chosen = resample<Connection>(
      strategy_, random, vertex.shading_point(), [&](const LightLiSample& s) { return connect(vertex, bsdf, s); });
  if (!chosen) return glm::vec3(0.0f);
  return shade(vertex, bsdf, chosen->kept, chosen->scale, rays);
}

glm::vec3 PathTracer::shade(const Vertex& vertex, const Bsdf& bsdf, const Connection& kept, float scale,
                            std::uint64_t& rays) const {
  const LightLiSample& light = kept.light;
  const glm::vec3& position = vertex.point.position;
  const glm::vec3& ng = vertex.point.geometric_normal;
  // Both ends pushed off their surfaces towards each other, so that neither blocks the ray; a
  // punctual light is approached short of its position, so that a fixture it sits on does not
  // hide it, and a directional one without end.
  const glm::vec3 origin = offset(position, ng, light.wi);
  glm::vec3 target;
  float length;
  if (light.delta) {
    target = light.distant() ? origin + light.wi : light.position;
    length = light.distant() ? kInfinity : glm::length(target - origin) * (1.0f - 1e-4f);
  } else {
    target = offset(light.position, light.normal, -light.wi);
    length = glm::length(target - origin);
  }
  if (!(length > 0.0f)) return glm::vec3(0.0f);
  const std::optional<Visibility> seen =
      visibility(origin, light.distant() ? light.wi : (target - origin) / glm::length(target - origin), length, rays);
  if (!seen) return glm::vec3(0.0f);
  glm::vec3 contribution = kept.unshadowed * seen->transmittance * scale;
  if (const Volume* medium = medium_along(scene_.materials[vertex.point.material], ng, light.wi))
    contribution *= medium->transmittance(light.distance);
  // No BSDF sample finds a delta light: its sample takes the whole weight.
  if (light.delta) return contribution;
  return contribution * power_heuristic(light.mis_pdf, bsdf.pdf(vertex.wo, light.wi) * seen->probability);
}

std::optional<PrimaryVertex> PathTracer::primary_vertex(const Ray& ray, std::uint64_t& rays) const {
  const std::optional<Hit> hit = geometry_.intersect(ray, kInfinity);
  ++rays;
  if (!hit) return std::nullopt;
  const SurfacePoint point = surface_point(scene_, *hit);
  PrimaryVertex v{*hit,
                  {point.position, point.shading_normal},
                  point.geometric_normal,
                  -ray.direction,
                  hit->distance,
                  Bsdf(surface_params(scene_, scene_.materials[point.material], point), point.shading_normal)};
  v.bsdf.prepare(v.wo);
  return v;
}

glm::vec3 PathTracer::unshadowed(const PrimaryVertex& v, const LightLiSample& s) const {
  if (is_black(s.li) || !consistent_sides(v.geometric_normal, v.at.normal, v.wo, s.wi)) return glm::vec3(0.0f);
  return v.bsdf.eval(v.wo, s.wi) * s.li;
}

}  // namespace tracer
