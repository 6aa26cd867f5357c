#pragma once
// Monte Carlo estimates of the radiance along one ray, with their standard error, for the
// tracer's statistical tests.

#include <cmath>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "tracer/emitters.h"
#include "tracer/geometry.h"
#include "tracer/light_strategy.h"
#include "tracer/path_tracer.h"

namespace trs_test {

struct Estimate {
  glm::dvec3 mean{0.0};
  glm::dvec3 standard_error{0.0};
};

/// `frames` passes of `paths` paths along `ray`, each connection resampled from the strategy's
/// candidates. Paths of one pass share its light set, so the error comes from the spread of the
/// pass means, which are independent.
inline Estimate estimate_radiance(const tracer::Scene& scene, const tracer::Geometry& geometry,
                                  const tracer::Emitters& emitters,
                                  tracer::LightStrategy& strategy, const tracer::Ray& ray,
                                  unsigned max_depth, unsigned frames, unsigned paths,
                                  std::uint64_t seed) {
  const tracer::PathTracer tracer(scene, geometry, emitters, strategy, max_depth);
  const lightsampler::PhiloxKey key = tracer::path_key(seed);
  glm::dvec3 sum(0.0), sum_squares(0.0);
  std::uint64_t rays = 0;
  for (unsigned f = 0; f < frames; ++f) {
    strategy.begin_pass(tracer::pass_seed(seed, f));
    glm::dvec3 frame(0.0);
    for (unsigned p = 0; p < paths; ++p) {
      tracer::PathRandom random(key, p, f);
      frame += glm::dvec3(tracer.radiance(ray, random, rays).radiance);
    }
    frame /= double(paths);
    sum += frame;
    sum_squares += frame * frame;
  }
  Estimate e;
  e.mean = sum / double(frames);
  const glm::dvec3 variance = (sum_squares / double(frames) - e.mean * e.mean) *
                              (double(frames) / double(frames - 1));
  e.standard_error = glm::sqrt(glm::max(variance, glm::dvec3(0.0)) / double(frames));
  return e;
}

/// Whether every channel of `e` lies within `sigmas` standard errors (plus `slack`, relative,
/// for the error of the expected value itself) of `expected`.
inline bool agrees(const Estimate& e, const glm::dvec3& expected, double sigmas, double slack) {
  for (int c = 0; c < 3; ++c) {
    if (std::abs(e.mean[c] - expected[c]) > sigmas * e.standard_error[c] + slack * expected[c])
      return false;
  }
  return true;
}

inline std::string describe(const Estimate& e, const glm::dvec3& expected) {
  std::string text;
  for (int c = 0; c < 3; ++c) {
    text += "channel " + std::to_string(c) + ": mean " + std::to_string(e.mean[c]) +
            " expected " + std::to_string(expected[c]) + " (" +
            std::to_string((e.mean[c] - expected[c]) / e.standard_error[c]) + " standard errors)\n";
  }
  return text;
}

}  // namespace trs_test
