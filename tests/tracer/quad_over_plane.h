#pragma once
// The tracer's analytic bench: an emissive quad with a known texture above a plane, and the
// radiance the plane reflects along one ray, direct lighting only, by quadrature over the texels.

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "estimate.h"
#include "registered_strategies.h"
#include "scene_builder.h"
#include "tracer/bsdf.h"

namespace trs_test {

using namespace tracer;

constexpr double kSigmas = 4.0;
constexpr double kQuadratureSlack = 1e-4;
constexpr unsigned kFrames = 400, kPaths = 500;
constexpr float kStrength = 3.0f;
constexpr std::uint32_t kTexWidth = 8, kTexHeight = 4;

/// The emitter covers [-0.5, 0.5]^2 at z = 1, facing down; the plane z = 0 faces up.
struct QuadOverPlane {
  Scene scene;
  glm::vec3 point{0.1f, 0.15f, 0.0f};                 ///< where the ray meets the plane
  glm::vec3 eye{0.45f, -0.1f, 0.3f};                  ///< where the ray starts
  std::unique_ptr<Geometry> geometry;
  std::unique_ptr<Emitters> emitters;

  /// `edit` changes the scene before its geometry and lights are built.
  explicit QuadOverPlane(const lightsampler::SamplerOptions& sampler = kCpuSampler,
                         const std::function<void(Scene&)>& edit = {}) {
    Material light;
    light.base_color = glm::vec3(0.0f);
    light.emissive_factor = glm::vec3(1.0f, 0.9f, 0.8f);
    light.emissive_strength = kStrength;
    light.emissive_texture.texture = add_random_texture(scene, kTexWidth, kTexHeight, 0.4, 3);
    const std::uint32_t emitter = add_material(scene, light);
    const std::uint32_t floor = add_material(scene, matte({0.8f, 0.6f, 0.4f}, 0.7f));
    // Corners in UV order (0,0) (1,0) (1,1) (0,1); clockwise seen from above: facing down.
    add_quad(scene, {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, 0.5f, 1},
                       {0.5f, -0.5f, 1}, emitter);
    add_quad(scene, {-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}, floor);
    if (edit) edit(scene);
    geometry = std::make_unique<Geometry>(scene);
    emitters = std::make_unique<Emitters>(scene, sampler);
  }

  Ray ray() const { return {eye, glm::normalize(point - eye)}; }

  /// Emitted radiance of texel (i, j): texture times factor times strength.
  glm::dvec3 radiance_at(std::uint32_t i, std::uint32_t j) const {
    const Material& m = scene.materials[0];
    const glm::vec3 t = scene.textures[0].texels[j * kTexWidth + i];
    return glm::dvec3(t * m.emissive_factor * m.emissive_strength);
  }

  /// The integral over the quad of f(wo, wi) Le cos(light) / r^2, midpoint rule on 16 x 16
  /// sub-cells of every texel (the integrand is smooth inside a texel).
  glm::dvec3 expected() const {
    return integrate([&](double u, double v) {
      return radiance_at(std::uint32_t(u * kTexWidth), std::uint32_t(v * kTexHeight));
    }, kTexWidth, kTexHeight);
  }

  /// The same integral of the emitted radiance `le` at the quad's (u, v), midpoint rule on
  /// 16 x 16 sub-cells of a grid of cells_u x cells_v cells, inside which `le` must be constant.
  glm::dvec3 integrate(const std::function<glm::dvec3(double u, double v)>& le_at, std::uint32_t cells_u,
                       std::uint32_t cells_v) const {
    return integrate_weighted(le_at, cells_u, cells_v, [](glm::vec3) { return glm::dvec3(1.0); });
  }

  /// The same with the light of each direction wi (unit, from the point to the quad) weighed by
  /// `weight(wi)`: what lies between the two lets through.
  glm::dvec3 integrate_weighted(const std::function<glm::dvec3(double u, double v)>& le_at, std::uint32_t cells_u,
                                std::uint32_t cells_v, const std::function<glm::dvec3(glm::vec3 wi)>& weight) const {
    const Material& m = scene.materials[1];
    const Bsdf bsdf({m.base_color, m.metallic, m.roughness}, {0, 0, 1});
    const glm::vec3 wo = glm::normalize(eye - point);
    constexpr int kSub = 16;
    glm::dvec3 sum(0.0);
    // add_quad gives corner k UV (0,0) (1,0) (1,1) (0,1); here those corners are
    // (-.5,-.5) (-.5,.5) (.5,.5) (.5,-.5): u runs along +y, v along +x.
    for (std::uint32_t j = 0; j < cells_v; ++j) {
      for (std::uint32_t i = 0; i < cells_u; ++i) {
        const glm::dvec3 le = le_at((i + 0.5) / cells_u, (j + 0.5) / cells_v);
        if (le == glm::dvec3(0.0)) continue;
        for (int a = 0; a < kSub; ++a) {
          for (int b = 0; b < kSub; ++b) {
            const double u = (i + (a + 0.5) / kSub) / cells_u;
            const double v = (j + (b + 0.5) / kSub) / cells_v;
            const glm::vec3 y(float(-0.5 + v), float(-0.5 + u), 1.0f);
            const glm::vec3 d = y - point;
            const float r2 = glm::dot(d, d);
            const glm::vec3 wi = d / std::sqrt(r2);
            const double cos_light = wi.z;  // the emitter faces -z
            const double area = 1.0 / (double(cells_u) * cells_v * kSub * kSub);
            sum += glm::dvec3(bsdf.eval(wo, wi)) * le * weight(wi) * (cos_light / r2 * area);
          }
        }
      }
    }
    return sum;
  }

  Estimate run(LightStrategy& strategy, std::uint64_t seed = 1) const {
    return estimate_radiance(scene, *geometry, *emitters, strategy, ray(), 1, kFrames, kPaths, seed);
  }
};

inline StrategyOptions options(const std::string& kind, double lights = 2000) {
  StrategyOptions o;
  o.kind = kind;
  o.lights = lights;
  return o;
}

inline std::unique_ptr<LightStrategy> strategy(Emitters& emitters, const std::string& kind,
                                        double lights = 2000) {
  return make_light_strategy(emitters, options(kind, lights));
}


/// Another strategy's draws, each connection resampled from `candidates` of them (as `ris` does),
/// for strategies the tests make.
class WithCandidates : public LightStrategy {
 public:
  WithCandidates(LightStrategy& source, unsigned candidates) : source_(source), candidates_(candidates) {}
  std::string name() const override { return source_.name(); }
  unsigned candidates() const override { return candidates_; }
  void begin_pass(std::uint64_t seed) override { source_.begin_pass(seed); }
  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    return source_.sample(random, at);
  }
  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return source_.pdf(light, b1, b2, from);
  }

 private:
  LightStrategy& source_;
  unsigned candidates_;
};

/// Deliberately wrong: lights drawn by one strategy and weighed (pdf, MIS) by another's density,
/// for showing that a check rejects a strategy whose draws and weights disagree.
class DrawnByOneWeighedByAnother : public LightStrategy {
 public:
  DrawnByOneWeighedByAnother(std::unique_ptr<LightStrategy> draws, std::unique_ptr<LightStrategy> weighs)
      : draws_(std::move(draws)), weighs_(std::move(weighs)) {}
  std::string name() const override { return "wrong"; }
  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    auto s = draws_->sample(random, at);
    if (s && !s->delta)
      s->pdf = s->mis_pdf =
          solid_angle_density(pdf(s->light, s->b1, s->b2, at), s->distance, glm::dot(-s->wi, s->normal));
    return s;
  }
  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint& from) const override {
    return weighs_->pdf(light, b1, b2, from);
  }

 private:
  std::unique_ptr<LightStrategy> draws_, weighs_;
};

}  // namespace trs_test
