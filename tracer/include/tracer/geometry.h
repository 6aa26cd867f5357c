#pragma once
// Ray queries against the scene's triangles. The only interface to the ray-tracing kernel
// (Embree 3); every Embree call lives in src/embree_geometry.cpp.

#include <cstdint>
#include <memory>
#include <optional>

#include "tracer/camera.h"
#include "tracer/scene.h"

namespace tracer {

/// The closest hit of a ray: triangle, barycentric weights of its second and third vertices
/// (as lightsampler's samples), and the distance along the unit direction.
struct Hit {
  std::uint32_t triangle;
  float b1;
  float b2;
  float distance;
};

class Geometry {
 public:
  /// Builds the acceleration structure over a copy of the scene's triangles. Where a material's
  /// alpha cuts or thins its surface (Material::alpha_mode), every query passes through the
  /// holes, and through a blended surface with probability 1 - alpha, decided by a hash of the
  /// ray and the triangle: the same ray always meets the same surfaces. The scene must outlive
  /// the geometry. Throws std::runtime_error if the kernel reports an error.
  explicit Geometry(const Scene& scene);
  ~Geometry();
  Geometry(const Geometry&) = delete;
  Geometry& operator=(const Geometry&) = delete;

  /// Closest hit with distance in (0, max_distance).
  std::optional<Hit> intersect(const Ray& ray, float max_distance) const;
  /// Whether anything lies along the ray at distance in (0, max_distance).
  bool occluded(const Ray& ray, float max_distance) const;
  /// Throws std::runtime_error with Embree's message if it reported an error during the queries
  /// (its error callback records them; queries themselves cannot throw).
  void throw_if_failed() const;

 private:
  struct Kernel;
  void add_triangles(const Scene& scene);
  std::unique_ptr<Kernel> kernel_;
};

}  // namespace tracer
