// The tracer's one contact with Embree 3: device, scene, one triangle geometry, and the two ray
// queries.

#include <embree3/rtcore.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <string>

#include "tracer/geometry.h"

namespace tracer {
namespace {

// What Embree reported through its error callback: the first error of the device, kept until
// it is thrown. The callback may run on any thread and must not throw into Embree.
struct ErrorLog {
  std::mutex mutex;
  std::string first;  ///< empty: no error so far

  static void record(void* log, RTCError code, const char* message) {
    auto& self = *static_cast<ErrorLog*>(log);
    const std::lock_guard lock(self.mutex);
    if (self.first.empty())
      self.first = "error " + std::to_string(int(code)) + (message ? std::string(": ") + message : std::string());
  }
};

RTCRay to_rtc(const Ray& ray, float max_distance) {
  RTCRay r{};
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x;
  r.dir_y = ray.direction.y;
  r.dir_z = ray.direction.z;
  r.tnear = 0.0f;
  r.tfar = max_distance;
  r.mask = 0xffffffffu;
  r.flags = 0;
  return r;
}

}  // namespace

struct Geometry::Kernel {
  ErrorLog errors;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  /// Throws std::runtime_error naming `what` and Embree's first error, if it reported one.
  void throw_on_error(const char* what) {
    const std::lock_guard lock(errors.mutex);
    const RTCError pending = device ? rtcGetDeviceError(device) : RTC_ERROR_NONE;
    if (errors.first.empty() && pending != RTC_ERROR_NONE) errors.first = "error " + std::to_string(int(pending));
    if (!errors.first.empty()) throw std::runtime_error(std::string("Embree: ") + what + " failed (" + errors.first + ")");
  }

  ~Kernel() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

Geometry::Geometry(const Mesh& mesh) : kernel_(std::make_unique<Kernel>()) {
  kernel_->device = rtcNewDevice(nullptr);
  if (!kernel_->device)
    throw std::runtime_error("Embree: could not create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(kernel_->device, &ErrorLog::record, &kernel_->errors);
  kernel_->scene = rtcNewScene(kernel_->device);
  rtcSetSceneBuildQuality(kernel_->scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(kernel_->scene, RTC_SCENE_FLAG_ROBUST);

  if (mesh.triangle_count() > 0) add_triangles(mesh);
  rtcCommitScene(kernel_->scene);
  kernel_->throw_on_error("building the scene");
}

void Geometry::add_triangles(const Mesh& mesh) {
  RTCGeometry triangles = rtcNewGeometry(kernel_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Buffers of Embree's own: it reads 16 bytes at the last vertex, past the end of a
  // std::vector<glm::vec3>.
  float* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      triangles, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3),
      mesh.positions.size()));
  unsigned* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      triangles, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
      mesh.triangle_count()));
  kernel_->throw_on_error("allocating the triangle buffers");
  std::copy_n(&mesh.positions[0].x, 3 * mesh.positions.size(), vertices);
  std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
  rtcCommitGeometry(triangles);
  rtcAttachGeometry(kernel_->scene, triangles);
  rtcReleaseGeometry(triangles);
}

Geometry::~Geometry() = default;

void Geometry::throw_if_failed() const { kernel_->throw_on_error("a ray query"); }

std::optional<Hit> Geometry::intersect(const Ray& ray, float max_distance) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit query{};
  query.ray = to_rtc(ray, max_distance);
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(kernel_->scene, &context, &query);
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return Hit{query.hit.primID, query.hit.u, query.hit.v, query.ray.tfar};
}

bool Geometry::occluded(const Ray& ray, float max_distance) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay query = to_rtc(ray, max_distance);
  rtcOccluded1(kernel_->scene, &context, &query);
  return query.tfar < 0.0f;  // Embree marks a hit by setting tfar to -inf
}

}  // namespace tracer
