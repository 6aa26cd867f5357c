#pragma once
// Input checks shared by every backend: bad input is a clear exception, never a crash.

#include <span>

#include "lightsampler/mesh.h"
#include "lightsampler/sampler.h"

namespace lightsampler::core {

/// Throws std::invalid_argument naming the first problem (what and where), or std::length_error
/// for 2^32 triangles or more.
void validate_mesh(const MeshView& mesh, std::size_t map_count);

/// Throws std::invalid_argument naming the map and the first bad texel.
void validate_map(const DensityMapView& map, std::size_t index);

/// Throws std::length_error when a mesh of this many triangles cannot be addressed by a Sample.
void validate_triangle_count(std::uint64_t triangles);

/// Throws std::invalid_argument for a target outside [0, 2^63] or max_tries of zero.
void validate_request(const FrameRequest& request);

/// Throws std::overflow_error when the density integrates to more than 2^63 samples.
void validate_expected_total(double total);

}  // namespace lightsampler::core
