#pragma once
// Pearson chi-square goodness-of-fit test, in the manner of pbrt-v4's bsdfs_test and Mitsuba 3's
// chi2.py: the expected counts come from somewhere independent of the sampler under test; a sample
// in a cell of expectation 0 fails the test outright; cells expected to hold fewer than 5 samples
// are pooled; the p-value is the regularized upper incomplete gamma function Q(dof/2, chi2/2).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace trs_test {

/// Regularized upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a), for a > 0, x >= 0.
double regularized_gamma_q(double a, double x);

/// P(X >= statistic) for X chi-square distributed with `dof` degrees of freedom; 1 when dof = 0.
double chi_square_p_value(double statistic, double dof);

/// Per-test significance that keeps the family-wise error rate of m independent tests at `alpha`
/// (Šidák): 1 - (1 - alpha)^(1/m).
double sidak_alpha(double alpha, std::size_t m);

/// One cell of the table after pooling: a run of input cells of the same group, merged.
struct PooledCell {
  std::size_t group = 0;       ///< which independent table it came from (see combine_independent)
  std::size_t first_cell = 0;  ///< input index of its first (smallest-expectation) member
  std::size_t cell_count = 0;  ///< input cells merged into it
  double observed = 0;
  double expected = 0;
  double contribution() const;  ///< (observed - expected)^2 / expected
};

/// A cell of expectation 0 that received samples: the test fails whatever the p-value.
struct ImpossibleCell {
  std::size_t group = 0;
  std::size_t cell = 0;
  double observed = 0;
};

struct ChiSquareResult {
  double statistic = 0;
  double dof = 0;
  double p_value = 1;
  double observed_total = 0;
  double expected_total = 0;
  std::vector<PooledCell> cells;
  std::vector<ImpossibleCell> impossible;

  /// No sample where none can be, and p-value >= alpha. A table with dof 0 (too few samples to
  /// test anything) passes: callers that need power check dof themselves.
  bool passes(double alpha) const { return impossible.empty() && p_value >= alpha; }
  /// Summary line, then the impossible cells and the `max_rows` pooled cells that contribute most.
  std::string describe(std::size_t max_rows = 20) const;
};

/// Compares observed with expected counts, cell by cell (same length). `constraints` is the number
/// of quantities the expected counts were fitted to: 1 when they sum to the observed total (the
/// usual multinomial case), 0 when they were fixed in advance. Throws std::invalid_argument on
/// mismatched lengths or on negative or non-finite entries.
ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected,
                                double constraints = 1, double min_expected = 5);

/// Sum of independent chi-square tests (e.g. one per triangle, each conditional on the triangle's
/// own count): statistics and degrees of freedom add. Each part's cells are tagged with its index.
ChiSquareResult combine_independent(std::span<const ChiSquareResult> parts);

}  // namespace trs_test
