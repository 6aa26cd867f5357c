#pragma once
// Benchmark meshes generated in-process (the GPU machine has no asset files or image libraries):
// a warped grid plane and a UV sphere, at a requested triangle count.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lightsampler/mesh.h"

namespace trs_bench {

enum class MeshKind { grid, sphere };

/// What to generate, as written on the command line: "grid:100k", "sphere:2M".
struct MeshSpec {
  MeshKind kind = MeshKind::grid;
  std::uint64_t triangles = 0;  ///< requested; the generated count is the nearest the shape allows
};

/// Parses "KIND:COUNT" with COUNT an integer, optionally suffixed k (1e3) or M (1e6). Throws
/// std::invalid_argument naming the bad spec.
MeshSpec parse_mesh_spec(std::string_view text);

struct Mesh {
  std::string name;  ///< "grid" or "sphere"
  std::vector<float> positions;
  std::vector<float> uvs;
  std::vector<std::uint32_t> indices;

  lightsampler::MeshView view() const { return {positions, uvs, indices, {}}; }
  std::uint64_t triangle_count() const { return indices.size() / 3; }
};

/// A plane whose grid is warped in UV and in world space differently, so that triangles vary in
/// texel footprint (up to ~9x per axis), in aspect, and in world-to-UV area ratio.
Mesh make_warped_grid(std::uint64_t triangles);

/// A latitude-longitude sphere with a UV seam; pole triangles are thin in world space but span a
/// full texel row band, the usual distortion of such meshes.
Mesh make_uv_sphere(std::uint64_t triangles);

Mesh make_mesh(const MeshSpec& spec);

}  // namespace trs_bench
