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

const char* to_string(Method method) {
  switch (method) {
    case Method::trs: return "trs";
    case Method::rejection: return "rs";
    case Method::naive: return "naive";
    case Method::frs: return "frs";
  }
  return "?";
}

const char* to_string(ScanOrder scan) {
  switch (scan) {
    case ScanOrder::automatic: return "auto";
    case ScanOrder::unordered: return "unordered";
    case ScanOrder::ordered: return "ordered";
    case ScanOrder::lookback: return "lookback";
  }
  return "?";
}

const char* to_string(Overlap overlap) {
  switch (overlap) {
    case Overlap::closed_form: return "closed-form";
    case Overlap::clipping: return "clipping";
    case Overlap::sdf: return "sdf";
  }
  return "?";
}

const char* to_string(Counting counting) {
  switch (counting) {
    case Counting::automatic: return "auto";
    case Counting::raster: return "raster";
    case Counting::compute: return "compute";
    case Counting::per_triangle: return "per-triangle";
    case Counting::cpu: return "cpu";
  }
  return "?";
}

const char* to_string(Backend backend) {
  switch (backend) {
    case Backend::automatic: return "auto";
    case Backend::cpu: return "cpu";
    case Backend::vulkan: return "vulkan";
  }
  return "?";
}

const char* to_string(Addressing addressing) {
  switch (addressing) {
    case Addressing::wrap: return "wrap";
    case Addressing::clamp: return "clamp";
    case Addressing::mirror: return "mirror";
  }
  return "?";
}

std::optional<Addressing> parse_addressing(std::string_view name) {
  for (const Addressing a : {Addressing::wrap, Addressing::clamp, Addressing::mirror})
    if (name == to_string(a)) return a;
  return std::nullopt;
}

const char* to_string(Pass pass) {
  switch (pass) {
    case Pass::counting: return "counting";
    case Pass::rounding: return "rounding";
    case Pass::scan: return "scan";
    case Pass::realization: return "realization";
    case Pass::distribution: return "distribution";
    case Pass::readback: return "readback";
    case Pass::refinement: return "refinement";
  }
  return "?";
}

unsigned worker_threads(const CpuOptions& options) {
  return options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace lightsampler
