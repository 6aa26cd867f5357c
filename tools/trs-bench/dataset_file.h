#pragma once
// Dataset files (.trsd): a mesh with UVs and a density map in one small binary file, so that
// trs-bench can run on assets (converted by trs-dataset, which has the image and scene loaders)
// on a machine without those libraries. Either part may be empty. Layout, little-endian, no
// padding (docs/benchmarks.md):
//
//   char[8]  magic "TRSDSET1"
//   u64      V, vertex count          u64  T, triangle count
//   u32      W, map width             u32  H, map height
//   f32      positions[3V], uvs[2V]   u32  indices[3T]   f32  texels[W*H] (row 0 at v = 0)

#include <filesystem>

#include "density_maps.h"
#include "meshes.h"

namespace trs_bench {

/// The file's mesh, named after the file's stem. Throws trs::FileError naming the file when it is
/// not a dataset file, is truncated, has no triangles, or has an index or coordinate out of range.
Mesh read_dataset_mesh(const std::filesystem::path& file);

/// The file's map, named after the file's stem. Throws trs::FileError naming the file when it is
/// not a dataset file, is truncated, has no map, or has a texel that is NaN, infinite or negative.
DensityMap read_dataset_map(const std::filesystem::path& file);

/// Writes `mesh` and `map` (either may be empty) atomically; throws trs::FileError on failure.
void write_dataset(const std::filesystem::path& file, const Mesh& mesh, const DensityMap& map);

}  // namespace trs_bench
