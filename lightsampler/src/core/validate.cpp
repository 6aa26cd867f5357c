#include "core/validate.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lightsampler::core {

namespace {

// Beyond 2^24 a float UV has no sub-unit precision left; texel lookups would be meaningless.
constexpr float kMaxAbsUv = 16777216.0f;

std::string vertex_problem(std::span<const float> values, int components, const char* what,
                           float max_abs) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float x = values[i];
    if (!std::isfinite(x))
      return std::string(what) + " of vertex " + std::to_string(i / components) + " is not finite";
    if (std::abs(x) > max_abs)
      return std::string(what) + " of vertex " + std::to_string(i / components) +
             " is out of range (|" + std::to_string(x) + "| > " + std::to_string(max_abs) + ")";
  }
  return {};
}

}  // namespace

void validate_triangle_count(std::uint64_t triangles) {
  if (triangles > 0xffffffffull)
    throw std::length_error("mesh has " + std::to_string(triangles) +
                            " triangles; at most 2^32 - 1 are supported");
}

namespace {
// Largest expected total accepted: counts are 64-bit, with headroom for the scan's packing.
constexpr double kMaxTotal = 0x1p63;
}  // namespace

void validate_request(const FrameRequest& request) {
  if (request.target_count &&
      !(std::isfinite(*request.target_count) && *request.target_count >= 0 &&
        *request.target_count <= kMaxTotal))
    throw std::invalid_argument("target count " + std::to_string(*request.target_count) +
                                " is not in [0, 2^63]");
  if (request.max_tries == 0) throw std::invalid_argument("max_tries must be at least 1");
}

void validate_expected_total(double total) {
  if (!(total <= kMaxTotal))
    throw std::overflow_error("the density integrates to " + std::to_string(total) +
                              " samples, more than 2^63; lower the density scale or set a target");
}

void validate_mesh(const MeshView& mesh, std::size_t map_count) {
  if (mesh.positions.size() % 3 != 0)
    throw std::invalid_argument("mesh positions: size " + std::to_string(mesh.positions.size()) +
                                " is not a multiple of 3");
  if (mesh.uvs.size() % 2 != 0)
    throw std::invalid_argument("mesh uvs: size " + std::to_string(mesh.uvs.size()) +
                                " is not a multiple of 2");
  if (mesh.uvs.size() / 2 != mesh.positions.size() / 3)
    throw std::invalid_argument("mesh has " + std::to_string(mesh.positions.size() / 3) +
                                " positions but " + std::to_string(mesh.uvs.size() / 2) + " uvs");
  if (mesh.indices.size() % 3 != 0)
    throw std::invalid_argument("mesh indices: size " + std::to_string(mesh.indices.size()) +
                                " is not a multiple of 3");
  const std::uint64_t triangles = mesh.triangle_count();
  validate_triangle_count(triangles);
  if (auto p = vertex_problem(mesh.positions, 3, "position", INFINITY); !p.empty())
    throw std::invalid_argument("mesh: " + p);
  if (auto p = vertex_problem(mesh.uvs, 2, "uv", kMaxAbsUv); !p.empty())
    throw std::invalid_argument("mesh: " + p);
  const std::uint64_t vertices = mesh.vertex_count();
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= vertices)
      throw std::invalid_argument("mesh: triangle " + std::to_string(i / 3) + " uses vertex " +
                                  std::to_string(mesh.indices[i]) + " but there are " +
                                  std::to_string(vertices) + " vertices");
  if (!mesh.triangle_maps.empty()) {
    if (mesh.triangle_maps.size() != triangles)
      throw std::invalid_argument("mesh: " + std::to_string(mesh.triangle_maps.size()) +
                                  " triangle map indices for " + std::to_string(triangles) +
                                  " triangles");
    for (std::size_t t = 0; t < mesh.triangle_maps.size(); ++t)
      if (mesh.triangle_maps[t] != kNoMap && mesh.triangle_maps[t] >= map_count)
        throw std::invalid_argument("mesh: triangle " + std::to_string(t) + " uses density map " +
                                    std::to_string(mesh.triangle_maps[t]) + " but there are " +
                                    std::to_string(map_count));
  }
}

void validate_map(const DensityMapView& map, std::size_t index) {
  const std::string name = "density map " + std::to_string(index);
  if (map.width == 0 || map.height == 0)
    throw std::invalid_argument(name + ": empty (" + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + ")");
  if (map.texels.size() != std::uint64_t(map.width) * map.height)
    throw std::invalid_argument(name + ": " + std::to_string(map.texels.size()) +
                                " texels for " + std::to_string(map.width) + "x" +
                                std::to_string(map.height));
  if (!std::isfinite(map.scale) || map.scale < 0)
    throw std::invalid_argument(name + ": scale " + std::to_string(map.scale) +
                                " is not a finite non-negative number");
  if (map.addressing != Addressing::wrap && map.addressing != Addressing::clamp &&
      map.addressing != Addressing::mirror)
    throw std::invalid_argument(name + ": unknown addressing mode");
  for (std::size_t i = 0; i < map.texels.size(); ++i) {
    const float d = map.texels[i];
    if (std::isfinite(d) && d >= 0) continue;
    const char* what = std::isnan(d) ? "NaN" : std::isinf(d) ? "infinite" : "negative";
    throw std::invalid_argument(name + ": texel (" + std::to_string(i % map.width) + ", " +
                                std::to_string(i / map.width) + ") is " + what +
                                "; densities must be finite and non-negative");
  }
}

}  // namespace lightsampler::core
