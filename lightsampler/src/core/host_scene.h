#pragma once
// The mesh and density maps as every backend keeps them on the host: validated copies, and the
// texel-space triangles that the realization and Sampler::density() read.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/density.h"
#include "core/geometry.h"
#include "lightsampler/mesh.h"
#include "lightsampler/texel_pieces.h"

namespace lightsampler::core {

/// `maps` checked, with `mesh`, as the samplers check them (validate.h: throws on bad input),
/// and copied.
std::vector<DensityMap> checked_maps(const MeshView& mesh, std::span<const DensityMapView> maps);

class HostScene {
 public:
  /// Throws std::invalid_argument / std::length_error on bad input (validate.h).
  HostScene(const MeshView& mesh, std::span<const DensityMapView> maps);

  /// Replaces map `index` (std::out_of_range for a bad index). Returns whether its size changed:
  /// then the texel-space triangles that use it were rebuilt.
  bool update_map(std::size_t index, const DensityMapView& map);

  /// Density at a point of a triangle, read as the samplers read it.
  float density(std::uint32_t triangle, float b1, float b2) const;
  /// The texel density() reads there.
  std::optional<Texel> texel(std::uint32_t triangle, float b1, float b2) const;
  /// Sampler::texel_pieces and Sampler::texel_piece_point.
  void texel_pieces(std::uint32_t triangle, std::vector<lightsampler::TexelPiece>& out) const;
  std::optional<Barycentrics> texel_piece_point(std::uint32_t triangle, std::int64_t cell_x,
                                                std::int64_t cell_y, float u_fan, float u0, float u1) const;

  std::span<const TriangleRecord> triangles() const { return triangles_; }
  std::span<const DensityMap> maps() const { return maps_; }
  std::span<const TexelTriangle> texel_triangles() const { return texel_triangles_; }

 private:
  static constexpr std::size_t kAllMaps = ~std::size_t(0);
  /// Texel-space triangles depend on their map's size (in parallel: meshes can be large).
  void build_texel_triangles(std::size_t map);
  /// Throws std::out_of_range for a triangle that does not exist.
  const TexelTriangle& texel_triangle(std::uint32_t triangle) const;

  std::vector<DensityMap> maps_;
  std::vector<TriangleRecord> triangles_;
  std::vector<TexelTriangle> texel_triangles_;
};

}  // namespace lightsampler::core
