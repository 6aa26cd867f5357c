#pragma once
// A pixel's camera ray, jittered by the first words of its path's stream: the renderer's passes
// and `auto`'s pilot take it alike, so that a pilot path is a render's path.

#include "tracer/camera.h"
#include "tracer/path_random.h"

namespace tracer {

inline Ray pixel_ray(const PinholeCamera& camera, unsigned x, unsigned y, PathRandom& random) {
  const auto jitter = random.floats();
  return camera.ray(float(x) + jitter[0], float(y) + jitter[1]);
}

}  // namespace tracer
