#pragma once
// Unidirectional path tracing with next-event estimation: at every surface point one light
// sample from the strategy and one BSDF sample, combined by multiple importance sampling with
// the power heuristic. Lights are the scene's emissive triangles and its punctual lights, which
// no BSDF sample finds; there is no environment. Smooth thin transmissive surfaces let paths and
// shadow rays straight through (Bsdf::pass_through); volumes absorb along the segments inside them.

#include <cstdint>
#include <optional>
#include <vector>


#include <glm/glm.hpp>

#include "tracer/bsdf.h"
#include "tracer/camera.h"
#include "tracer/emitters.h"
#include "tracer/geometry.h"
#include "tracer/light_strategy.h"
#include "tracer/path_random.h"
#include "tracer/scene.h"

namespace tracer {

/// Power heuristic (beta = 2) weight of a technique of density `a` against one of density `b`.
inline float power_heuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/// One path's estimate.
struct PathEstimate {
  glm::vec3 radiance{0.0f};
  bool sees_emitter = false;  ///< the camera ray's first hit is an emitter
  /// The part of `radiance` emitted where the camera ray met a surface (straight through panes):
  /// no light sample takes part in it, so its noise is the same whatever the strategy.
  glm::vec3 seen_emission{0.0f};
  /// Next-event queries the strategy answered along the path, each with strategy.candidates()
  /// light samples weighed: the work `auto`'s pilot counts.
  std::uint32_t light_queries = 0;
};

/// The first surface a camera ray meets, where `restir` keeps its pixel's reservoir: the point
/// light samples are seen from, and the BSDF that weighs them.
struct PrimaryVertex {
  Hit hit;
  ShadingPoint at;
  glm::vec3 geometric_normal;
  glm::vec3 wo;     ///< unit, towards the camera
  float distance;   ///< from the camera
  Bsdf bsdf;        ///< prepared for wo: any thread may query it with wo (Bsdf::prepare)
};

class PathTracer {
 public:
  /// `max_depth`: most surface interactions a path scatters at; 0 shows emitters only, 1 is
  /// direct lighting. Each connection is resampled from strategy.candidates() light samples.
  PathTracer(const Scene& scene, const Geometry& geometry, const Emitters& emitters,
             const LightStrategy& strategy, unsigned max_depth);

  /// What `restir` found along a camera ray before its path: the ray's first hit, and the light
  /// sample that lights it (its reservoir's, whose `pdf` is the reciprocal of its contribution
  /// weight in solid angle; none: lit by nothing).
  struct FirstSurface {
    std::optional<Hit> hit;
    std::optional<LightLiSample> light;
  };

  /// Radiance arriving along `ray` (one estimate); adds the rays it traces to `rays`. With
  /// `first`, the ray's first hit is first->hit, traced already, and lit by first->light instead
  /// of by the strategy's light sample.
  PathEstimate radiance(Ray ray, PathRandom& random, std::uint64_t& rays, const FirstSurface* first = nullptr) const;

  /// The first surface `ray` meets, where radiance() would take a light sample (none: it meets
  /// nothing). Adds the ray to `rays`.
  std::optional<PrimaryVertex> primary_vertex(const Ray& ray, std::uint64_t& rays) const;
  /// What light sample `s` brings to `v` unshadowed, f Li (its density left out); zero where it
  /// brings nothing.
  glm::vec3 unshadowed(const PrimaryVertex& v, const LightLiSample& s) const;

 private:
  struct Vertex;
  struct Connection;
  struct Visibility;
  std::optional<Connection> connect(const Vertex& vertex, const Bsdf& bsdf,
                                    const LightLiSample& light) const;
  /// `from`: the vertex the BSDF sample left, where the light strategy would have been asked.
  glm::vec3 emitted(const Vertex& vertex, float bsdf_pdf, const ShadingPoint* from, float distance) const;
  /// What a shadow ray from `origin` along unit `direction` lets through over `length`; none
  /// where it is blocked. Counts the rays it traces.
  std::optional<Visibility> visibility(glm::vec3 origin, glm::vec3 direction, float length,
                                       std::uint64_t& rays) const;
  glm::vec3 light_sample(const Vertex& vertex, const Bsdf& bsdf, PathRandom& random,
                         std::uint64_t& rays) const;
  /// What `kept` brings through the shadow ray, times `scale`, weighed against BSDF sampling.
  glm::vec3 shade(const Vertex& vertex, const Bsdf& bsdf, const Connection& kept, float scale,
                  std::uint64_t& rays) const;

  const Scene& scene_;
  const Geometry& geometry_;
  const Emitters& emitters_;
  const LightStrategy& strategy_;
  unsigned max_depth_;
  /// Per material: whether it may let light straight through (surface.h), and whether any does.
  std::vector<bool> pass_through_materials_;
  bool any_pass_through_ = false;
};

}  // namespace tracer
