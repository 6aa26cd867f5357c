#pragma once
// A sample on the mesh, and what can be read off it.

#include <cstdint>

#include "lightsampler/mesh.h"

namespace lightsampler {

/// A point on triangle `triangle`: p = (1 - b1 - b2) v0 + b1 v1 + b2 v2.
struct Sample {
  std::uint32_t triangle;
  float b1;
  float b2;
};
static_assert(sizeof(Sample) == 12);

struct Float2 {
  float x, y;
};
struct Float3 {
  float x, y, z;
};

/// World position of a sample on the mesh it was drawn from.
Float3 position(const MeshView& mesh, const Sample& s);
/// Texture coordinates of a sample (interpolated vertex UVs).
Float2 uv(const MeshView& mesh, const Sample& s);
/// Unit geometric normal of the sample's triangle, (v1 - v0) x (v2 - v0) normalised; zero for a
/// degenerate triangle.
Float3 geometric_normal(const MeshView& mesh, const Sample& s);

}  // namespace lightsampler
