#pragma once
// Triangle meshes with UVs from Wavefront OBJ and glTF 2.0 (.gltf, .glb) files.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "lightsampler/mesh.h"
#include "lightsampler/sample.h"

namespace trs {

/// Where a file puts v = 0. The library's convention (and glTF's) is `top`: image row 0, the
/// first row as images are stored and read, is at v = 0. OBJ's v points up: v = 0 is the bottom.
enum class UvOrigin { top, bottom };

/// A mesh loaded from a file and owned here; UVs are stored in the library's convention whatever
/// the file's, and `file_uv_origin` records the file's so that outputs can speak its language.
struct MeshData {
  std::filesystem::path file;
  UvOrigin file_uv_origin = UvOrigin::top;
  std::vector<float> positions;        ///< 3 per vertex, world space
  std::vector<float> uvs;              ///< 2 per vertex, library convention
  std::vector<std::uint32_t> indices;  ///< 3 per triangle

  lightsampler::MeshView view() const;
  std::uint64_t triangle_count() const { return indices.size() / 3; }
};

/// Loads an OBJ (triangulated; every face needs UVs) or the TRIANGLES primitives of a glTF
/// file's default scene (world transforms applied; TEXCOORD_0 required). Chooses the format by
/// the extension. Throws FileError naming the file and the problem.
MeshData load_mesh(const std::filesystem::path& file);

/// The triangles of a glTF file's primitives that use material `material` (glTF's index), as
/// load_mesh loads them: one emitter's triangles. Throws FileError naming the file, also when
/// no triangle uses it.
MeshData load_gltf_material(const std::filesystem::path& file, int material);

/// A UV of the library's convention, as a file of convention `origin` states it.
lightsampler::Float2 to_file_uv(lightsampler::Float2 uv, UvOrigin origin);

}  // namespace trs
