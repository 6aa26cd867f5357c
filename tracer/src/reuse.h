#pragma once
// `restir`: spatiotemporal reuse of resampled light samples at the first surface of each camera
// ray (Bitterli et al. 2020, "Spatiotemporal reservoir resampling for real-time ray tracing with
// dynamic direct lighting"), made unbiased by generalized RIS (Lin et al. 2022, "Generalized
// Resampled Importance Sampling"). Every pass, each pixel:
// 1. resamples its strategy's candidates (ris's) into a reservoir: one light sample y and its
//    unbiased contribution weight W, for the target p(y) = luminance of f Li G, unshadowed (in
//    area measure on the triangles, counting measure on the punctual lights);
// 2. where asked, combines it with its own reservoir of the pass before (temporal; the camera is
//    fixed within a frame), counted at most as `m_cap` passes' candidates;
// 3. combines that with the step-2 reservoirs of a few neighbours within a radius, each rejected
//    where its surface's normal or distance differs too much (spatial).
// Each combination weighs reservoir i's sample y with MIS weights m_i(y) that sum to one wherever
// the pixel's own target is above zero, so the combined W stays an unbiased contribution weight
// (p_j: the target at reservoir j's own surface, M_j its candidates, c the pixel's own):
// - pairwise (the default; Bitterli 2022, "Correlations and reuse for fast and accurate physically
//   based light transport", ch. 9): each neighbour i is weighed against the pixel's own reservoir
//   alone, m_i(y) = s_i M_i p_i(y) / (M_i p_i(y) + M_c/n p_c(y)) with share
//   s_i = (M_i + M_c/n) / sum_j M_j over the n neighbours, and the pixel's own sample takes what
//   the pairs leave; 2n target evaluations a pixel;
// - balance, the generalized balance heuristic, m_i(y) = M_i p_i(y) / sum_j M_j p_j(y):
//   n(n+2) evaluations. The kept sample is shaded with its shadow ray (visibility is never
// reused) and weighed against BSDF sampling with the strategy's own density, as `ris`'s are.
// Deeper vertices keep `ris`. A new animation frame, or a new render, starts without history.

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tracer/light_strategy.h"
#include "tracer/path_random.h"
#include "tracer/path_tracer.h"

namespace tracer {

/// The most neighbours a pixel's reservoir is combined with in a pass.
constexpr unsigned kMaxNeighbours = 64;

/// The streams of the reservoirs' candidates and of the choice of neighbours, apart from the paths'.
constexpr std::uint64_t kGatherStream = 0x676174686572ull, kSpatialStream = 0x7370617469616cull;

/// What the reuse did beside the paths' own work: the reservoirs it gathered (each a camera
/// ray's first surface, shaded and kept), the candidates they weighed (each a light sample of the
/// strategy) and its evaluations of the target at a surface (each a light point seen from it and
/// its BSDF). `auto`'s pilot counts them at their unit costs.
struct ReuseWork {
  std::uint64_t reservoirs = 0, candidates = 0, targets = 0;
  ReuseWork& operator+=(const ReuseWork& o) {
    reservoirs += o.reservoirs;
    candidates += o.candidates;
    targets += o.targets;
    return *this;
  }
};

struct ReuseOptions {
  /// spatial: neighbours' reservoirs combined per pass; 0: no spatial reuse. Eight within six
  /// pixels gain as much as `ris` with 64 candidates on lights whose texels decide
  /// (docs/noise.md, "Reuse across pixels and passes").
  unsigned neighbours = 8;
  float radius = 6.0f;  ///< spatial: how far the neighbours are, in pixels
  /// temporal: the most a reservoir of earlier passes counts for, in passes' candidates (its M cap)
  float m_cap = 20.0f;
  /// Reuse each pixel's reservoir of the pass before. Off unless asked: the passes of an image
  /// then share samples, and on the shipped scenes that costs more than the reuse gains
  /// (docs/noise.md, "Reuse across pixels and passes").
  bool temporal = false;
  /// How a combination weighs its reservoirs' samples: pairwise or by the generalized balance
  /// heuristic (both unbiased), or in proportion to their M alone (Bitterli et al. 2020's 1/M
  /// weights: cheapest, and biased, darker, where neighbouring surfaces see different lights).
  enum class Weights { pairwise, balance, uniform } weights = Weights::pairwise;
};

/// restir's options from --strategy-option NAME=VALUE (neighbours, radius, m-cap, temporal,
/// weights).
/// Throws std::invalid_argument naming the option and the value it cannot take.
ReuseOptions reuse_options(const std::map<std::string, std::string>& parameters);

/// The reuse `strategy` asks for: restir's options; none for the other strategies.
const ReuseOptions* reuse_of(const LightStrategy& strategy);

/// The reservoirs of a render's pixels, and the passes' reuse.
class Reuse {
 public:
  Reuse(const PathTracer& tracer, const Emitters& emitters, const LightStrategy& strategy, const ReuseOptions& options,
        unsigned width, unsigned height);

  /// Forgets every reservoir: the next pass has no pass before it.
  void reset();
  /// Starts a pass: this pass's reservoirs become the pass before's.
  void begin_pass();
  /// Step 1 and 2 for `pixel`, whose camera ray is `ray`. Adds the rays it traces to `rays`, and
  /// its other work to `work`.
  void gather(std::uint32_t pixel, const Ray& ray, PathRandom& random, std::uint64_t& rays, ReuseWork& work);
  /// Step 3 for `pixel`, once every pixel gathered; adds its work to `work`.
  void spatial(std::uint32_t pixel, PathRandom& random, ReuseWork& work);
  /// What `pixel`'s path starts from (PathTracer::radiance's `first`): its camera ray's hit, and
  /// the light sample that lights it, none where the reservoir holds nothing.
  PathTracer::FirstSurface first_surface(std::uint32_t pixel) const;

  /// One sample of a reservoir: a point of a triangle, or a punctual light (point.light).
  struct Sample {
    LightPoint point;  ///< its densities 1: seen from a surface, its pdf is 1 / G
    bool punctual = false;
  };
  struct Reservoir {
    std::optional<Sample> y;
    float target = 0.0f;  ///< p(y) at the reservoir's own surface
    float W = 0.0f;       ///< unbiased contribution weight
    float M = 0.0f;       ///< candidates it stands for
  };

 private:
  struct Input;
  // Each adds the targets it evaluates to `targets`.
  Reservoir combine(std::span<const Input> inputs, PathRandom& random, std::uint64_t& targets) const;
  /// Input i's MIS weight for its own sample, given p_0 of it (the target at inputs[0]'s surface)
  /// and the inputs' total M.
  float weight(std::span<const Input> inputs, std::size_t i, float p_0, float total, std::uint64_t& targets) const;
  float balance(std::span<const Input> inputs, std::size_t i, std::uint64_t& targets) const;
  float pairwise(std::span<const Input> inputs, std::size_t i, float p_0, float total, std::uint64_t& targets) const;
  /// `y` seen from `at`, its densities those of a unit area density (pdf = 1 / G); none where
  /// it is not seen.
  std::optional<LightLiSample> seen(const Sample& y, const ShadingPoint& at) const;
  float target(const PrimaryVertex& v, const Sample& y, std::uint64_t& targets) const;

  const PathTracer& tracer_;
  const Emitters& emitters_;
  const LightStrategy& strategy_;
  ReuseOptions options_;
  unsigned width_, height_;
  // Per pixel: its first surface and reservoirs, this pass's and the pass before's.
  std::vector<std::optional<PrimaryVertex>> vertices_, previous_vertices_;
  std::vector<Reservoir> temporal_, final_, previous_final_;
};

}  // namespace tracer
