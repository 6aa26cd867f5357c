#pragma once
// Walker's alias method, built by Vose's algorithm: an index drawn in proportion to its weight in
// constant time. One 64-bit uniform word chooses both the column and the coin: the column is the
// high word of word x size (Lemire), the coin its low word, uniform to about size / 2^64.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace tracer {

class AliasTable {
 public:
  /// `weights` non-negative and finite, with a positive sum; std::invalid_argument otherwise.
  explicit AliasTable(std::span<const double> weights);

  struct Pick {
    std::size_t index;
    double u;  ///< what the choice left of the word: a fresh uniform in [0, 1)
  };
  Pick sample(std::uint64_t word) const;

  /// The probability sample() gives `index`, as the table holds it.
  double probability(std::size_t index) const;

  std::size_t size() const { return columns_.size(); }
  std::size_t bytes() const { return columns_.capacity() * sizeof(Column); }

 private:
  struct Column {
    double threshold;     ///< the coin below which the column's own index is drawn
    std::uint32_t alias;  ///< drawn otherwise
  };
  std::vector<Column> columns_;
};

}  // namespace tracer
