#include "strategies/alias_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tracer {

AliasTable::AliasTable(std::span<const double> weights) : columns_(weights.size()) {
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
    columns_[s] = {share[s], l};
    share[l] -= 1.0 - share[s];
    if (share[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What rounding leaves on either list is a full column.
  for (const std::uint32_t i : large) columns_[i] = {1.0, i};
  for (const std::uint32_t i : small) columns_[i] = {1.0, i};
}

namespace {

__extension__ using Uint128 = unsigned __int128;  // GCC's and Clang's; ISO C++ has none

}  // namespace

AliasTable::Pick AliasTable::sample(std::uint64_t word) const {
  const Uint128 product = Uint128(word) * columns_.size();
  const auto column = std::size_t(product >> 64);
  const double coin = double(std::uint64_t(product) >> 11) * 0x1p-53;  // in [0, 1) exactly
  const Column& c = columns_[column];
  if (coin < c.threshold) return {column, coin / c.threshold};
  return {c.alias, std::min((coin - c.threshold) / (1.0 - c.threshold), 0x1.fffffffffffffp-1)};
}

double AliasTable::probability(std::size_t index) const {
  double p = columns_[index].threshold;
  for (const Column& c : columns_)
    if (c.alias == index && c.threshold < 1.0) p += 1.0 - c.threshold;
  return p / double(columns_.size());
}

}  // namespace tracer
