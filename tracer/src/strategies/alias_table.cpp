#include "strategies/alias_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "strategies/unit_interval.h"

namespace tracer::alias {
namespace {

__extension__ using Uint128 = unsigned __int128;  // GCC's and Clang's; ISO C++ has none


}  // namespace

void build(std::span<const double> weights, std::span<Column> columns) {
  if (weights.size() >= (std::size_t(1) << 32))
    throw std::invalid_argument("an alias table holds fewer than 2^32 entries");
  double total = 0.0;
  for (const double w : weights) {
    if (!(w >= 0.0 && std::isfinite(w))) throw std::invalid_argument("alias table weights must be finite and non-negative");
    total += w;
  }
  if (!(total > 0.0)) throw std::invalid_argument("alias table weights sum to zero");
  // Vose: each column's share times n, split into columns below 1 and columns of 1 or more; a
  // small column is topped up from a large one, which becomes small or stays large.
  const double n = double(weights.size());
  std::vector<double> share(weights.size());
  std::vector<std::uint32_t> small, large;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    share[i] = weights[i] / total * n;
    (share[i] < 1.0 ? small : large).push_back(std::uint32_t(i));
  }
  while (!small.empty() && !large.empty()) {
    const std::uint32_t s = small.back(), l = large.back();
    small.pop_back();
    columns[s] = {float(share[s]), l};
    share[l] -= 1.0 - share[s];
    if (share[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What rounding leaves on either list is a full column.
  for (const std::uint32_t i : large) columns[i] = {1.0f, i};
  for (const std::uint32_t i : small) columns[i] = {1.0f, i};
}

Pick sample(std::span<const Column> columns, std::uint64_t word) {
  const Uint128 product = Uint128(word) * columns.size();
  const auto column = std::size_t(product >> 64);
  const double coin = double(std::uint64_t(product) >> 11) * 0x1p-53;  // in [0, 1) exactly
  const Column& c = columns[column];
  const double threshold = c.threshold;
  if (coin < threshold) return {column, coin / threshold};
  return {c.alias, below_one((coin - threshold) / (1.0 - threshold))};
}

double probability(std::span<const Column> columns, std::size_t index) {
  double p = columns[index].threshold;
  for (const Column& c : columns)
    if (c.alias == index && c.threshold < 1.0f) p += 1.0 - double(c.threshold);
  return p / double(columns.size());
}

}  // namespace tracer::alias
