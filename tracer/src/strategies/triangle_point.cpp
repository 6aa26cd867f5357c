#include "strategies/triangle_point.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <lightsampler/random.h>

#include "strategies/piece_table.h"
#include "strategies/spherical_triangle.h"
#include "strategies/unit_interval.h"

namespace tracer {

std::optional<LightLiSample> TrianglePoint::sample(const LightPick& pick, const LightRandom& random, int first,
                                                   const ShadingPoint& at) const {
  const std::optional<PointOnLight> p = draw(pick.light, random, first, at);
  if (!p) return std::nullopt;
  // A point seen edge-on, or in a texel without density, carries nothing; pdf() gives it zero too.
  const auto density = float(pick.pmf * p->density);
  if (!(density > 0.0f)) return std::nullopt;
  const Light light = emitters_.light(pick.light);
  return light.sample_li(light.point(p->b.b1, p->b.b2, density, density), at);
}

float TrianglePoint::pdf(double pmf, std::uint32_t light, float b1, float b2, const ShadingPoint& from) const {
  return float(pmf * density(light, b1, b2, from));
}

namespace {

class AreaPoint : public TrianglePoint {
 public:
  explicit AreaPoint(const Emitters& emitters) : TrianglePoint(emitters) {}

  std::optional<PointOnLight> draw(std::uint32_t light, const LightRandom& random, int first,
                                   const ShadingPoint&) const override {
    return PointOnLight{lightsampler::triangle_map(lightsampler::uniform_float(random[first]),
                                                   lightsampler::uniform_float(random[first + 1])),
                        1.0 / emitters_.area(light)};
  }
  double density(std::uint32_t light, float, float, const ShadingPoint&) const override {
    return 1.0 / emitters_.area(light);
  }
};

/// Solid angles, in steradians, between which a triangle is sampled by direction. Below, cos
/// theta_l / d^2 varies too little over the triangle for sampling by direction to pay for its
/// trigonometry: pbrt-v4 starts at 3e-4 sr, which on the shipped scenes costs up to 26% more time
/// per frame for at most 4% less noise (docs/noise.md); from 0.1 sr, a 1 m^2 panel 3 m
/// away, it pays. Above 6.22 sr (pbrt-v4's) the triangle fills nearly the whole hemisphere and
/// Arvo's construction loses precision.
constexpr double kMinSphericalSolidAngle = 0.1;
constexpr double kMaxSphericalSolidAngle = 6.22;

class SolidAnglePoint : public TrianglePoint {
 public:
  explicit SolidAnglePoint(const Emitters& emitters) : TrianglePoint(emitters) {}

  std::optional<PointOnLight> draw(std::uint32_t light, const LightRandom& random, int first,
                                   const ShadingPoint& at) const override {
    const std::array<glm::vec3, 3> v = emitters_.vertices(light);
    const double omega = spherical_solid_angle(v, at.position);
    const float u1 = lightsampler::uniform_float(random[first]), u2 = lightsampler::uniform_float(random[first + 1]);
    const lightsampler::Barycentrics b = by_direction(omega) ? sample_spherical_triangle(v, at.position, u1, u2)
                                                             : lightsampler::triangle_map(u1, u2);
    return PointOnLight{b, point_density(light, b.b1, b.b2, at, omega)};
  }

  double density(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return point_density(light, b1, b2, from, spherical_solid_angle(emitters_.vertices(light), from.position));
  }

 private:
  static bool by_direction(double omega) {
    return omega >= kMinSphericalSolidAngle && omega <= kMaxSphericalSolidAngle;
  }

  /// The triangle's solid angle seen from `p` where it may be sampled by direction, zero where
  /// the solid angle of its bounding sphere (about its centroid) shows that it is too small: most
  /// lights are far, and that test needs no trigonometry.
  static double spherical_solid_angle(const std::array<glm::vec3, 3>& v, const glm::vec3& p) {
    const glm::dvec3 centroid = (glm::dvec3(v[0]) + glm::dvec3(v[1]) + glm::dvec3(v[2])) / 3.0;
    double r2 = 0.0;
    for (const glm::vec3& corner : v) r2 = std::max(r2, glm::dot(glm::dvec3(corner) - centroid, glm::dvec3(corner) - centroid));
    const glm::dvec3 d = centroid - glm::dvec3(p);
    const double d2 = glm::dot(d, d);
    // A sphere of radius r at distance D subtends 2 pi (1 - sqrt(1 - r^2 / D^2)).
    if (d2 > r2 && 2.0 * std::numbers::pi * (1.0 - std::sqrt(1.0 - r2 / d2)) < kMinSphericalSolidAngle) return 0.0;
    return solid_angle(v, p);
  }

  /// Area density of point (b1, b2) of `light` as drawn for `at`, given the light's solid angle
  /// there: uniform by area, or uniform by direction, whose area density is |cos theta_l| / (d^2
  /// omega).
  float point_density(std::uint32_t light, float b1, float b2, const ShadingPoint& at, double omega) const {
    if (!by_direction(omega)) return 1.0f / emitters_.area(light);
    const glm::dvec3 d = glm::dvec3(emitters_.position(light, b1, b2)) - glm::dvec3(at.position);
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0.0)) return 0.0f;
    const double cos_light = std::abs(glm::dot(glm::dvec3(emitters_.normal(light)), d)) / std::sqrt(d2);
    return float(cos_light / (d2 * omega));
  }
};

class TexelPoint : public TrianglePoint {
 public:
  explicit TexelPoint(const Emitters& emitters) : TrianglePoint(emitters) { build(); }

  void emission_changed() override { build(); }

  std::optional<PointOnLight> draw(std::uint32_t light, const LightRandom& random, int first,
                                   const ShadingPoint&) const override {
    // With image-mean powers a tree may pick a light that emits nothing.
    if (!(table_->light_weight(light) > 0.0)) return std::nullopt;
    const PieceTable::Pick piece = table_->pick_in_light(light, word64(random, first));
    const lightsampler::Barycentrics b =
        table_->point(piece.piece, below_one_float(piece.u), lightsampler::uniform_float(random[first + 2]),
                      lightsampler::uniform_float(random[first + 3]));
    // Rounding can put a point on its cell's edge into the neighbouring texel: its density is
    // what that texel reads, as density() gives it.
    return PointOnLight{b, density_in_light(light, b.b1, b.b2)};
  }

  double density(std::uint32_t light, float b1, float b2, const ShadingPoint&) const override {
    return table_->light_weight(light) > 0.0 ? density_in_light(light, b1, b2) : 0.0;
  }

  StrategySetup setup() const override { return {build_ms_, table_->bytes()}; }

 private:
  void build() {
    const auto start = std::chrono::steady_clock::now();
    table_.emplace(emitters_);
    build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  /// D(y) / Phi_T: the density of a point within its light.
  float density_in_light(std::uint32_t light, float b1, float b2) const {
    return float(double(emitters_.density(light, b1, b2)) / table_->light_weight(light));
  }

  std::optional<PieceTable> table_;
  double build_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<TrianglePoint> make_area_point(const Emitters& emitters) { return std::make_unique<AreaPoint>(emitters); }
std::unique_ptr<TrianglePoint> make_solid_angle_point(const Emitters& emitters) {
  return std::make_unique<SolidAnglePoint>(emitters);
}
std::unique_ptr<TrianglePoint> make_texel_point(const Emitters& emitters) { return std::make_unique<TexelPoint>(emitters); }

}  // namespace tracer
