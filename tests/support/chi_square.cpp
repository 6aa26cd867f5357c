#include "support/chi_square.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace trs_test {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
constexpr double kTiny = std::numeric_limits<double>::min() / kEpsilon;

/// Both expansions need O(sqrt(a)) terms near x = a; beyond this cap something is wrong.
int max_iterations(double a) { return 1000 + static_cast<int>(100 * std::sqrt(a)); }

/// x^a e^-x / Gamma(a), the factor shared by both expansions, in logs to avoid overflow.
double gamma_prefactor(double a, double x) { return std::exp(a * std::log(x) - x - std::lgamma(a)); }

/// Lower P(a, x) by its power series; converges fast for x < a + 1.
double gamma_p_series(double a, double x) {
  double term = 1 / a, sum = term;
  for (int n = 1, limit = max_iterations(a); n < limit; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEpsilon) return sum * gamma_prefactor(a, x);
  }
  throw std::runtime_error("regularized_gamma_q: series did not converge");
}

/// Upper Q(a, x) by its continued fraction (modified Lentz); converges fast for x >= a + 1.
double gamma_q_continued_fraction(double a, double x) {
  double b = x + 1 - a;
  double c = 1 / kTiny;
  double d = 1 / b;
  double h = d;
  for (int i = 1, limit = max_iterations(a); i < limit; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < kEpsilon) return h * gamma_prefactor(a, x);
  }
  throw std::runtime_error("regularized_gamma_q: continued fraction did not converge");
}

void append(std::string& out, const char* format, auto... args) {
  char line[512];
  std::snprintf(line, sizeof line, format, args...);
  out += line;
}

}  // namespace

double regularized_gamma_q(double a, double x) {
  if (!(a > 0) || !(x >= 0)) throw std::invalid_argument("regularized_gamma_q: needs a > 0, x >= 0");
  if (x == 0) return 1;
  if (std::isinf(x)) return 0;
  // Q = 1 - P only where P is not close to 1, so the subtraction loses nothing that matters.
  return x < a + 1 ? 1 - gamma_p_series(a, x) : gamma_q_continued_fraction(a, x);
}

double chi_square_p_value(double statistic, double dof) {
  if (std::isnan(statistic)) return statistic;
  if (dof <= 0 || statistic <= 0) return 1;
  return regularized_gamma_q(dof / 2, statistic / 2);
}

double sidak_alpha(double alpha, std::size_t m) {
  if (m == 0) throw std::invalid_argument("sidak_alpha: needs at least one test");
  // 1 - (1 - alpha)^(1/m) without the cancellation of the naive form for large m.
  return -std::expm1(std::log1p(-alpha) / static_cast<double>(m));
}

double PooledCell::contribution() const {
  const double diff = observed - expected;
  return diff * diff / expected;
}

ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected,
                                double constraints, double min_expected) {
  if (observed.size() != expected.size())
    throw std::invalid_argument("chi_square_test: observed and expected differ in length");
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (!std::isfinite(observed[i]) || !std::isfinite(expected[i]) || observed[i] < 0 || expected[i] < 0)
      throw std::invalid_argument("chi_square_test: cell " + std::to_string(i) + " is negative or not finite");
  }
  ChiSquareResult result;
  result.observed_total = std::accumulate(observed.begin(), observed.end(), 0.0);
  result.expected_total = std::accumulate(expected.begin(), expected.end(), 0.0);

  // Smallest expectations first, so that pooling merges the cells that need it with each other.
  std::vector<std::size_t> order(observed.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return expected[i] < expected[j]; });

  PooledCell pool;
  for (std::size_t i : order) {
    if (expected[i] == 0) {
      if (observed[i] > 0) result.impossible.push_back({0, i, observed[i]});
      continue;
    }
    if (pool.cell_count == 0) pool.first_cell = i;
    pool.cell_count += 1;
    pool.observed += observed[i];
    pool.expected += expected[i];
    if (pool.expected >= min_expected) {
      result.cells.push_back(pool);
      pool = PooledCell{};
    }
  }
  // Left-over small cells (all cells below min_expected from here on) join the last pool.
  if (pool.cell_count > 0) {
    if (result.cells.empty()) {
      result.cells.push_back(pool);
    } else {
      result.cells.back().cell_count += pool.cell_count;
      result.cells.back().observed += pool.observed;
      result.cells.back().expected += pool.expected;
    }
  }

  for (const PooledCell& cell : result.cells) result.statistic += cell.contribution();
  result.dof = std::max(static_cast<double>(result.cells.size()) - constraints, 0.0);
  result.p_value = chi_square_p_value(result.statistic, result.dof);
  return result;
}

ChiSquareResult combine_independent(std::span<const ChiSquareResult> parts) {
  ChiSquareResult sum;
  for (std::size_t g = 0; g < parts.size(); ++g) {
    const ChiSquareResult& part = parts[g];
    sum.statistic += part.statistic;
    sum.dof += part.dof;
    sum.observed_total += part.observed_total;
    sum.expected_total += part.expected_total;
    for (PooledCell cell : part.cells) {
      cell.group = g;
      sum.cells.push_back(cell);
    }
    for (ImpossibleCell cell : part.impossible) {
      cell.group = g;
      sum.impossible.push_back(cell);
    }
  }
  sum.p_value = chi_square_p_value(sum.statistic, sum.dof);
  return sum;
}

std::string ChiSquareResult::describe(std::size_t max_rows) const {
  std::string out;
  append(out, "chi-square %.6g, dof %.0f, p-value %.6g; %zu cells after pooling; observed total %.17g, expected total %.17g\n",
         statistic, dof, p_value, cells.size(), observed_total, expected_total);
  if (!impossible.empty()) {
    append(out, "%zu cells of expected count 0 received samples (the test fails whatever the p-value):\n",
           impossible.size());
    for (std::size_t i = 0; i < std::min(max_rows, impossible.size()); ++i)
      append(out, "  group %zu cell %zu: observed %.17g\n", impossible[i].group, impossible[i].cell, impossible[i].observed);
  }
  std::vector<PooledCell> worst = cells;
  const std::size_t rows = std::min(max_rows, worst.size());
  std::partial_sort(worst.begin(), worst.begin() + static_cast<std::ptrdiff_t>(rows), worst.end(),
                    [](const PooledCell& p, const PooledCell& q) { return p.contribution() > q.contribution(); });
  append(out, "largest contributions:\n%8s %10s %8s %14s %14s %12s\n", "group", "first cell", "merged", "observed",
         "expected", "(o-e)^2/e");
  for (std::size_t i = 0; i < rows; ++i) {
    const PooledCell& c = worst[i];
    append(out, "%8zu %10zu %8zu %14.6g %14.6g %12.4g\n", c.group, c.first_cell, c.cell_count, c.observed, c.expected,
           c.contribution());
  }
  return out;
}

}  // namespace trs_test
