#pragma once
// Benchmark meshes generated in-process (the GPU machine has no asset files or image libraries):
// a warped grid plane, a UV sphere and a displaced torus in a UV atlas, at a requested triangle
// count. A mesh may also come from a dataset file (dataset_file.h).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "lightsampler/mesh.h"

namespace trs_bench {

enum class MeshKind { grid, sphere, torus, file };

/// What to make, as written on the command line: "grid:100k", "sphere:2M", "file:lamp.trsd".
struct MeshSpec {
  MeshKind kind = MeshKind::grid;
  std::uint64_t triangles = 0;  ///< requested; the generated count is the nearest the shape allows
  std::filesystem::path file;   ///< file: the dataset file
};

/// Parses "KIND:COUNT" with COUNT an integer, optionally suffixed k (1e3) or M (1e6), or
/// "file:PATH". Throws std::invalid_argument naming the bad spec.
MeshSpec parse_mesh_spec(std::string_view text);

struct Mesh {
  std::string name;  ///< "grid", "sphere", "torus", or a dataset file's name
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

/// A torus whose tube radius is displaced by a few bumps, unwrapped into four charts (quarters of
/// the ring) packed in a 2x2 atlas with gaps, one chart mirrored and two turned by 90 degrees:
/// UV seams, unused texels and triangles of every orientation, as an artist's unwrap has.
Mesh make_displaced_torus(std::uint64_t triangles);

/// A generated mesh, or the mesh of a dataset file.
Mesh make_mesh(const MeshSpec& spec);

}  // namespace trs_bench
