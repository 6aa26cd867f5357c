#pragma once
// Walker's alias method, built by Vose's algorithm: an index drawn in proportion to its weight in
// constant time. One 64-bit uniform word chooses both the column and the coin: the column is the
// high word of word x size (Lemire), the coin its low word, uniform to about size / 2^64. What the
// choice leaves of the word is a fresh uniform.
//
// A table is a span of columns; PieceTable keeps one per light in a single array.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace tracer::alias {

struct Column {
  float threshold;      ///< the coin below which the column's own index is drawn
  std::uint32_t alias;  ///< drawn otherwise, an index within the table
};

/// Fills `columns` (one per weight) for weights non-negative and finite, with a positive sum;
/// throws std::invalid_argument otherwise.
void build(std::span<const double> weights, std::span<Column> columns);

struct Pick {
  std::size_t index;
  double u;  ///< what the choice left of the word: a uniform in [0, 1)
};
Pick sample(std::span<const Column> columns, std::uint64_t word);

/// The probability sample() gives `index`, as the columns hold it.
double probability(std::span<const Column> columns, std::size_t index);

/// A table that owns its columns.
class Table {
 public:
  explicit Table(std::span<const double> weights) : columns_(weights.size()) { build(weights, columns_); }
  Pick sample(std::uint64_t word) const { return alias::sample(columns_, word); }
  std::size_t bytes() const { return columns_.capacity() * sizeof(Column); }

 private:
  std::vector<Column> columns_;
};

}  // namespace tracer::alias
