#pragma once
// Primary rays of a pinhole camera.

#include <glm/glm.hpp>

#include "tracer/scene.h"

namespace tracer {

struct Ray {
  glm::vec3 origin;
  glm::vec3 direction;  ///< unit
};

class PinholeCamera {
 public:
  /// The image is width x height pixels; the camera's aspect ratio, when it states one, wins
  /// over the image's (the image is then stretched, as glTF viewers do).
  PinholeCamera(const Camera& camera, unsigned width, unsigned height);

  /// The ray through image point (x, y), in pixels from the top-left corner.
  Ray ray(float x, float y) const;

 private:
  glm::vec3 origin_;
  glm::vec3 top_left_;  ///< direction to the image's top-left corner at unit distance
  glm::vec3 step_x_;    ///< change of direction per pixel to the right
  glm::vec3 step_y_;    ///< change of direction per pixel down
};

/// A camera that frames a bounding box, looking down -z at it, for scenes without one.
Camera framing_camera(glm::vec3 lower, glm::vec3 upper);

}  // namespace tracer
