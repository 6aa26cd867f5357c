#pragma once
// Fast rejection sampling's table (Šik and Křivánek, "Fast Random Sampling of Triangular
// Meshes", 2013), built once on the host and shared by every backend: the mesh subdivided until
// the density is nearly constant on each micro-triangle, and one CDF of area times bound over
// them. A frame then draws micro-triangles from the CDF, a uniform point on each, and rejects
// against the micro-triangle's bound (cpu/frs.h, shaders/frs.comp).
//
// Subdivision rule: a triangle (or part) splits into four at its edge midpoints while its
// expected acceptance (mean density over the bound) is below kFrsAcceptance, it spans more than
// kFrsMinTexels texels, and it is fewer than kFrsMaxDepth splits deep. Parts without density
// are dropped. Bounds are taken over every lattice cell of a part's bounding box widened by a
// hair, so that no density read at a point of the part exceeds its bound.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/density.h"
#include "core/geometry.h"
#include "lightsampler/buffer.h"

namespace lightsampler::core {

inline constexpr double kFrsAcceptance = 0.9;
inline constexpr double kFrsMinTexels = 1.0;
inline constexpr int kFrsMaxDepth = 10;

/// The micro-triangles and their CDF: what FRS keeps between frames.
struct FrsTable {
  std::vector<std::uint32_t> parent;               ///< the caller's triangle
  std::vector<std::array<float, 6>> corners;        ///< barycentrics (b1, b2) of its 3 corners in the parent
  std::vector<float> bound;                         ///< D^max over the micro-triangle
  Buffer<double> cdf;                               ///< inclusive CDF of world area times bound
  std::vector<std::uint32_t> guide;                 ///< the CDF's cutpoints (core/area_pick.h)
  double expected_total = 0.0;                      ///< N-bar, the integral of the density
  double total_area = 0.0;                          ///< world area of the micro-triangles kept
  float max_bound = 0.0f;

  std::size_t size() const { return parent.size(); }
  /// Memory the table holds, bytes.
  std::uint64_t bytes() const;
};

/// Subdivides every triangle by the rule above and builds the CDF.
FrsTable frs_build(std::span<const TriangleRecord> records,
                   std::span<const TexelTriangle> triangles, std::span<const DensityMap> maps);

}  // namespace lightsampler::core
