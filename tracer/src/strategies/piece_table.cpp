#include "strategies/piece_table.h"

#include <array>
#include <atomic>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include <lightsampler/texel_pieces.h>

namespace tracer {
namespace {

/// Pieces of one light, as the table keeps them.
struct LightPieces {
  std::vector<std::array<std::int32_t, 2>> cells;
  std::vector<double> weights;
};

bool fits_int32(std::int64_t v) {
  return v >= std::numeric_limits<std::int32_t>::min() && v <= std::numeric_limits<std::int32_t>::max();
}

std::string too_many(std::size_t max_pieces) {
  return "the lights have more than " + std::to_string(max_pieces) +
         " pieces of lit texels, the most a texel piece table takes (docs/limits.md); trs draws the "
         "same density without a table";
}

}  // namespace

PieceTable::PieceTable(const Emitters& emitters, std::size_t max_pieces)
    : emitters_(emitters), first_(emitters.count() + 1, 0), light_weight_(emitters.count(), 0.0) {
  const lightsampler::Sampler& sampler = emitters.sampler();
  std::vector<LightPieces> lights(emitters.count());
  std::atomic<std::size_t> total{0};
  // Cut in parallel, light by light; stop as soon as the limit is passed, before the memory is.
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, emitters.count()),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      std::vector<lightsampler::TexelPiece> pieces;
                      for (std::uint32_t l = range.begin(); l != range.end(); ++l) {
                        sampler.maps().texel_pieces(l, pieces);
                        if (total.fetch_add(pieces.size()) + pieces.size() > max_pieces) return;
                        const double area = emitters.area(l);
                        for (const lightsampler::TexelPiece& p : pieces) {
                          if (!fits_int32(p.cell_x) || !fits_int32(p.cell_y))
                            throw std::invalid_argument("a light's UVs reach beyond 2^31 texels");
                          lights[l].cells.push_back({std::int32_t(p.cell_x), std::int32_t(p.cell_y)});
                          lights[l].weights.push_back(double(p.density) * p.area * area);
                        }
                      }
                    });
  if (total > max_pieces) throw std::invalid_argument(too_many(max_pieces));
  cells_.reserve(total);
  weights_.reserve(total);
  for (std::uint32_t l = 0; l < emitters.count(); ++l) {
    first_[l] = cells_.size();
    for (std::size_t i = 0; i < lights[l].cells.size(); ++i) {
      cells_.push_back({l, lights[l].cells[i][0], lights[l].cells[i][1]});
      weights_.push_back(lights[l].weights[i]);
      light_weight_[l] += lights[l].weights[i];
    }
    total_weight_ += light_weight_[l];
    lights[l] = {};
  }
  first_.back() = cells_.size();
  columns_.resize(cells_.size());
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, emitters.count()),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      for (std::uint32_t l = range.begin(); l != range.end(); ++l) {
                        const std::size_t n = first_[l + 1] - first_[l];
                        if (n > 0 && light_weight_[l] > 0.0)
                          alias::build(std::span(weights_).subspan(first_[l], n),
                                       std::span(columns_).subspan(first_[l], n));
                      }
                    });
}

PieceTable::Pick PieceTable::pick_in_light(std::uint32_t light, std::uint64_t word) const {
  const std::size_t first = first_[light];
  const alias::Pick pick = alias::sample(std::span(columns_).subspan(first, first_[light + 1] - first), word);
  return {first + pick.index, pick.u};
}

lightsampler::Barycentrics PieceTable::point(std::size_t piece, float u_fan, float u0, float u1) const {
  const Cell& c = cells_[piece];
  // The same cut as when the table was built: the cell's piece exists.
  return *emitters_.sampler().maps().texel_piece_point(c.light, c.x, c.y, u_fan, u0, u1);
}

std::size_t PieceTable::bytes() const {
  return cells_.capacity() * sizeof(Cell) + weights_.capacity() * sizeof(double) +
         columns_.capacity() * sizeof(alias::Column) + first_.capacity() * sizeof(std::size_t) +
         light_weight_.capacity() * sizeof(double);
}

}  // namespace tracer
