#pragma once
// A point on an emissive triangle once a light choice picked it (pbrt-v4's Light::SampleLi for
// its triangles): uniform by area; uniform by solid angle where the triangle subtends enough of
// it; or by the triangle's texels. Each gives the point's area density within the triangle, and
// density() gives it again for a point a BSDF sample found.

#include <cstdint>
#include <memory>
#include <optional>

#include <lightsampler/triangle_map.h>

#include "strategies/point_draw.h"

namespace tracer {

struct PointOnLight {
  lightsampler::Barycentrics b;
  double density;  ///< per world area, within the light
};

/// A point on the triangle the choice picked, its densities the pick's probability times the
/// point's density within the triangle.
class TrianglePoint : public PointDraw {
 public:
  explicit TrianglePoint(const Emitters& emitters) : emitters_(emitters) {}

  std::optional<LightLiSample> sample(const LightPick& pick, const LightRandom& random, int first,
                                      const ShadingPoint& at) const final;
  float pdf(double pmf, std::uint32_t light, float b1, float b2, const ShadingPoint& from) const final;

 protected:
  /// A point of `light` seen from `at`, read from the words of `random` from `first` on; none
  /// where the light offers nothing there.
  virtual std::optional<PointOnLight> draw(std::uint32_t light, const LightRandom& random, int first,
                                           const ShadingPoint& at) const = 0;
  /// The area density within `light` with which draw() gives point (b1, b2) from `from`.
  virtual double density(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const = 0;

  const Emitters& emitters_;
};

/// Uniform by area: density 1 / area.
std::unique_ptr<TrianglePoint> make_area_point(const Emitters& emitters);
/// Uniform in the solid angle the triangle subtends where that lies between 0.1 and 6.22 sr,
/// uniform by area otherwise.
std::unique_ptr<TrianglePoint> make_solid_angle_point(const Emitters& emitters);
/// A texel piece of the triangle in proportion to density times area, then a uniform point in
/// it: density D(y) / Phi_T, Phi_T the triangle's integral of D.
std::unique_ptr<TrianglePoint> make_texel_point(const Emitters& emitters);

}  // namespace tracer
