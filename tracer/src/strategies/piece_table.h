#pragma once
// Every texel piece of the scene's lights with non-zero density (lightsampler's texel pieces:
// a light cut along its emission map's texels), light by light, with an alias table per light
// over its pieces' weights, density times world area. A point drawn in a piece chosen by weight
// has density D(x) / (the weights' sum): the target density of `trs`, drawn exactly at every
// query instead of through a frame's point set. `tree-texel` picks a piece within the light the
// tree picked; `texel` picks one over the whole scene with a table of its own.
//
// Memory: 28 bytes per piece: the light and the lattice cell (the piece's polygon is cut again
// from its cell when drawn in, a few clips), its weight, and its column of the light's alias
// table.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <lightsampler/triangle_map.h>

#include "strategies/alias_table.h"
#include "tracer/emitters.h"

namespace tracer {

class PieceTable {
 public:
  /// Most pieces a table holds: 235 MB, and 300 MB with the texel strategy's alias table. A
  /// 2048 x 2048 emission map lit everywhere has 4.2 million.
  static constexpr std::size_t kMaxPieces = std::size_t(1) << 23;

  /// Throws std::invalid_argument when the lights have more than `max_pieces` pieces of
  /// non-zero density. With none (the lights emit nothing), the table is empty.
  explicit PieceTable(const Emitters& emitters, std::size_t max_pieces = kMaxPieces);

  std::size_t size() const { return cells_.size(); }
  std::uint32_t light(std::size_t piece) const { return cells_[piece].light; }
  /// Every piece's weight, in order: light by light.
  std::span<const double> weights() const { return weights_; }
  /// A light's weight: its pieces', summed; zero for a light without any.
  double light_weight(std::uint32_t light) const { return light_weight_[light]; }
  double total_weight() const { return total_weight_; }

  struct Pick {
    std::size_t piece;
    double u;  ///< what the choice left of the word: a fresh uniform in [0, 1)
  };
  /// A piece of `light` in proportion to its weight, from a uniform 64-bit word; the light must
  /// have a positive weight.
  Pick pick_in_light(std::uint32_t light, std::uint64_t word) const;

  /// A uniform point of the piece, from three uniforms in [0, 1).
  lightsampler::Barycentrics point(std::size_t piece, float u_fan, float u0, float u1) const;

  std::size_t bytes() const;

 private:
  struct Cell {
    std::uint32_t light;
    std::int32_t x, y;  ///< the lattice cell (texel_pieces.h)
  };
  const Emitters& emitters_;
  std::vector<Cell> cells_;
  std::vector<double> weights_;               ///< per piece
  std::vector<alias::Column> columns_;        ///< per piece, its light's table
  std::vector<std::size_t> first_;            ///< per light, its first piece; one more at the end
  std::vector<double> light_weight_;
  double total_weight_ = 0.0;
};

}  // namespace tracer
