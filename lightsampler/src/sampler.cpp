#include "lightsampler/sampler.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace lightsampler {

namespace {

Float3 vertex(const MeshView& mesh, std::uint32_t triangle, int corner) {
  const std::uint32_t v = mesh.indices[3 * std::size_t(triangle) + corner];
  return {mesh.positions[3 * std::size_t(v)], mesh.positions[3 * std::size_t(v) + 1],
          mesh.positions[3 * std::size_t(v) + 2]};
}

Float2 vertex_uv(const MeshView& mesh, std::uint32_t triangle, int corner) {
  const std::uint32_t v = mesh.indices[3 * std::size_t(triangle) + corner];
  return {mesh.uvs[2 * std::size_t(v)], mesh.uvs[2 * std::size_t(v) + 1]};
}

}  // namespace

Float3 position(const MeshView& mesh, const Sample& s) {
  const Float3 a = vertex(mesh, s.triangle, 0), b = vertex(mesh, s.triangle, 1),
               c = vertex(mesh, s.triangle, 2);
  const float b0 = 1.0f - s.b1 - s.b2;
  return {b0 * a.x + s.b1 * b.x + s.b2 * c.x, b0 * a.y + s.b1 * b.y + s.b2 * c.y,
          b0 * a.z + s.b1 * b.z + s.b2 * c.z};
}

Float2 uv(const MeshView& mesh, const Sample& s) {
  const Float2 a = vertex_uv(mesh, s.triangle, 0), b = vertex_uv(mesh, s.triangle, 1),
               c = vertex_uv(mesh, s.triangle, 2);
  const float b0 = 1.0f - s.b1 - s.b2;
  return {b0 * a.x + s.b1 * b.x + s.b2 * c.x, b0 * a.y + s.b1 * b.y + s.b2 * c.y};
}

Float3 geometric_normal(const MeshView& mesh, const Sample& s) {
  const Float3 a = vertex(mesh, s.triangle, 0), b = vertex(mesh, s.triangle, 1),
               c = vertex(mesh, s.triangle, 2);
  const Float3 e1{b.x - a.x, b.y - a.y, b.z - a.z}, e2{c.x - a.x, c.y - a.y, c.z - a.z};
  const Float3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const float len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  if (!(len > 0)) return {0, 0, 0};
  return {n.x / len, n.y / len, n.z / len};
}

unsigned worker_threads(const CpuOptions& options) {
  return options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace lightsampler
