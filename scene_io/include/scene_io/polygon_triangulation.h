#pragma once
// Triangulation of the polygons of polygonal mesh formats (OBJ faces with more than 3 corners).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "lightsampler/sample.h"

namespace trs {

/// Splits a polygon, given by its corner positions in order, into triangles of corner indices
/// (n - 2 of them for n corners). Ear clipping in the plane of the polygon's Newell normal, so a
/// concave polygon is covered exactly once; a polygon too degenerate to clip falls back to a fan.
std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(
    std::span<const lightsampler::Float3> corners);

}  // namespace trs
