#include "strategies/piece_table.h"

#include <algorithm>
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
    : emitters_(emitters), first_(emitters.count() + 1, 0) {
  const lightsampler::Sampler& sampler = emitters.sampler();
  std::vector<LightPieces> lights(emitters.count());
  std::atomic<std::size_t> total{0};
  // Cut in parallel, light by light; stop as soon as the limit is passed, before the memory is.
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, emitters.count()),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      std::vector<lightsampler::TexelPiece> pieces;
                      for (std::uint32_t l = range.begin(); l != range.end(); ++l) {
                        sampler.texel_pieces(l, pieces);
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
  if (total == 0) throw std::invalid_argument("the lights emit nothing: no texel piece to draw from");
  cells_.reserve(total);
  running_.reserve(total);
  for (std::uint32_t l = 0; l < emitters.count(); ++l) {
    first_[l] = cells_.size();
    double sum = 0.0;
    for (std::size_t i = 0; i < lights[l].cells.size(); ++i) {
      cells_.push_back({l, lights[l].cells[i][0], lights[l].cells[i][1]});
      running_.push_back(sum += lights[l].weights[i]);
    }
    total_weight_ += sum;
    lights[l] = {};
  }
  first_.back() = cells_.size();
}

double PieceTable::weight(std::size_t piece) const {
  const std::size_t first = first_[cells_[piece].light];
  return piece == first ? running_[piece] : running_[piece] - running_[piece - 1];
}

double PieceTable::light_weight(std::uint32_t light) const {
  return first_[light + 1] > first_[light] ? running_[first_[light + 1] - 1] : 0.0;
}

PieceTable::Pick PieceTable::pick_in_light(std::uint32_t light, double u) const {
  const auto begin = running_.begin() + std::ptrdiff_t(first_[light]);
  const auto end = running_.begin() + std::ptrdiff_t(first_[light + 1]);
  const double target = u * *(end - 1);
  // The first piece whose running weight exceeds the target: pieces of zero weight never are.
  const auto it = std::min(std::upper_bound(begin, end, target), end - 1);
  const std::size_t piece = std::size_t(it - running_.begin());
  const double below = it == begin ? 0.0 : *(it - 1);
  const double rest = std::clamp((target - below) / (*it - below), 0.0, 0x1.fffffffffffffp-1);
  return {piece, rest};
}

lightsampler::Barycentrics PieceTable::point(std::size_t piece, float u_fan, float u0, float u1) const {
  const Cell& c = cells_[piece];
  // The same cut as when the table was built: the cell's piece exists.
  const std::optional<lightsampler::TexelPiece> p = emitters_.sampler().texel_piece(c.light, c.x, c.y);
  return lightsampler::uniform_point(*p, u_fan, u0, u1);
}

std::size_t PieceTable::bytes() const {
  return cells_.capacity() * sizeof(Cell) + running_.capacity() * sizeof(double) +
         first_.capacity() * sizeof(std::size_t);
}

}  // namespace tracer
