#include "tracer/camera.h"

#include <cmath>

namespace tracer {

PinholeCamera::PinholeCamera(const Camera& camera, unsigned width, unsigned height)
    : origin_(camera.position) {
  const float aspect = camera.aspect > 0.0f ? camera.aspect : float(width) / float(height);
  const float half_height = std::tan(0.5f * camera.yfov);
  const float half_width = aspect * half_height;
  const glm::vec3 right = glm::normalize(glm::cross(camera.forward, camera.up));
  const glm::vec3 up = glm::cross(right, camera.forward);
  top_left_ = camera.forward - half_width * right + half_height * up;
  step_x_ = (2.0f * half_width / float(width)) * right;
  step_y_ = (-2.0f * half_height / float(height)) * up;
}

Ray PinholeCamera::ray(float x, float y) const {
  return {origin_, glm::normalize(top_left_ + x * step_x_ + y * step_y_)};
}

Camera framing_camera(glm::vec3 lower, glm::vec3 upper) {
  Camera camera;
  const glm::vec3 center = 0.5f * (lower + upper);
  const float radius = 0.5f * glm::length(upper - lower);
  // Far enough back that a sphere around the box fits the vertical field of view.
  const float distance = radius / std::sin(0.5f * camera.yfov) + 1e-3f;
  camera.position = center + glm::vec3(0.0f, 0.0f, distance);
  return camera;
}

}  // namespace tracer
