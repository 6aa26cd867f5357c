#pragma once
// Sample sets as binary little-endian PLY point clouds, one vertex per sample:
//   float x, y, z     world position
//   float u, v        UV in the mesh file's own convention (see MeshData::file_uv_origin)
//   uint triangle     the triangle's index in the loaded mesh
//   float b1, b2      barycentric weights of the triangle's second and third vertices

#include <cstdint>
#include <span>
#include <string>

#include "scene_io/atomic_file.h"
#include "scene_io/mesh_io.h"
#include "lightsampler/sample.h"

namespace trs {

/// Bytes per sample in the file.
inline constexpr std::size_t kPlyBytesPerSample = 32;

/// The header of a file of `count` samples, ending with "end_header\n".
std::string ply_header(std::uint64_t count, UvOrigin uv_origin);

/// Writes header and samples. Samples are converted in parallel (in the caller's TBB arena), in
/// chunks, while the previous chunk is being written, so that 10^8 samples take about as long
/// as writing 3.2 GB does.
void write_ply(AtomicFile& out, const MeshData& mesh,
               std::span<const lightsampler::Sample> samples);

}  // namespace trs
