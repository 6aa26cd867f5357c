// The tracer's one contact with Embree 3: device, scene, one triangle geometry, and the two ray
// queries.

#include <embree3/rtcore.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>

#include "tracer/geometry.h"

#include "surface.h"

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

/// A uniform float in [0, 1) from a ray and a triangle (splitmix64's finaliser over their bits),
/// for stochastic transparency: independent of the path's random stream, so that a query needs
/// no state and a ray met twice (as Embree may test a triangle twice) decides alike.
float ray_hash(RTCRayN* ray, unsigned n, unsigned i, unsigned triangle) {
  const float values[6] = {RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i),
                           RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)};
  std::uint64_t h = triangle;
  for (const float value : values) {
    h = (h ^ std::bit_cast<std::uint32_t>(value)) + 0x9e3779b97f4a7c15ull;
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    h ^= h >> 31;
  }
  return float(h >> 40) * 0x1p-24f;
}

/// Embree's filter for both queries: drops a candidate hit where the surface is a hole, and on
/// a blended surface with probability 1 - alpha.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto& scene = *static_cast<const Scene*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
    const float alpha = opacity(scene, triangle, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    if (alpha >= 1.0f) continue;
    if (alpha <= 0.0f || ray_hash(args->ray, args->N, i, triangle) >= alpha) args->valid[i] = 0;
  }
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

Geometry::Geometry(const Scene& scene) : kernel_(std::make_unique<Kernel>()) {
  kernel_->device = rtcNewDevice(nullptr);
  if (!kernel_->device)
    throw std::runtime_error("Embree: could not create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(kernel_->device, &ErrorLog::record, &kernel_->errors);
  kernel_->scene = rtcNewScene(kernel_->device);
  rtcSetSceneBuildQuality(kernel_->scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(kernel_->scene, RTC_SCENE_FLAG_ROBUST);

  if (scene.mesh.triangle_count() > 0) add_triangles(scene);
  rtcCommitScene(kernel_->scene);
  kernel_->throw_on_error("building the scene");
}

void Geometry::add_triangles(const Scene& scene) {
  const Mesh& mesh = scene.mesh;
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
  if (std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.alpha_tested(); })) {
    rtcSetGeometryUserData(triangles, const_cast<Scene*>(&scene));  // read only, by alpha_filter
    rtcSetGeometryIntersectFilterFunction(triangles, &alpha_filter);
    rtcSetGeometryOccludedFilterFunction(triangles, &alpha_filter);
  }
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
