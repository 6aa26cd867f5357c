// Tests of the chi-square helper itself: if it were wrong, every statistical test built on it
// would be meaningless.

#include "support/chi_square.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace trs_test {
namespace {

/// Q(a, x) for a half-integer or integer a > 0 by the exact recurrence
/// Q(a + 1, x) = Q(a, x) + x^a e^-x / Gamma(a + 1), from Q(1/2, x) = erfc(sqrt x) or Q(1, x) = e^-x:
/// an oracle sharing nothing with the series / continued fraction under test.
double q_by_recurrence(double a, double x) {
  const bool half = std::fmod(a, 1.0) != 0;
  double base = half ? 0.5 : 1.0;
  double q = half ? std::erfc(std::sqrt(x)) : std::exp(-x);
  for (; base < a; base += 1) q += std::exp(base * std::log(x) - x - std::lgamma(base + 1));
  return q;
}

TEST(ChiSquare, TabulatedCriticalValues) {
  // Upper 5 % and 1 % points of the chi-square distribution (e.g. NIST/SEMATECH e-Handbook,
  // Table 1.3.6.7.4). The 1-dof values are the squares of the normal quantiles 1.959963984540054
  // and 2.5758293035489004.
  EXPECT_NEAR(chi_square_p_value(3.841458820694124, 1), 0.05, 1e-12);
  EXPECT_NEAR(chi_square_p_value(6.6348966010212145, 1), 0.01, 1e-12);
  EXPECT_NEAR(chi_square_p_value(18.307, 10), 0.05, 1e-5);
  EXPECT_NEAR(chi_square_p_value(23.209, 10), 0.01, 1e-5);
  EXPECT_NEAR(chi_square_p_value(124.342, 100), 0.05, 1e-5);
  EXPECT_EQ(chi_square_p_value(0, 1), 1.0);
  EXPECT_EQ(chi_square_p_value(0, 10), 1.0);
  EXPECT_EQ(chi_square_p_value(5, 0), 1.0);
}

TEST(ChiSquare, GammaQMatchesExactRecurrence) {
  // Both branches (series for x < a + 1, continued fraction beyond), small and large a, far tails.
  for (double a : {0.5, 1.0, 1.5, 2.0, 5.0, 10.5, 50.0, 250.5, 1000.0}) {
    for (double ratio : {0.01, 0.1, 0.5, 0.9, 1.0, 1.1, 1.5, 2.0, 4.0}) {
      const double x = a * ratio;
      const double exact = q_by_recurrence(a, x);
      // The oracle's own rounding grows with the number of recurrence steps.
      const double tolerance = 1e-13 * (1 + a) * exact + 1e-300;
      EXPECT_NEAR(regularized_gamma_q(a, x), exact, tolerance) << "a " << a << " x " << x;
    }
  }
}

TEST(ChiSquare, GammaQEdgeArguments) {
  EXPECT_EQ(regularized_gamma_q(3, 0), 1.0);
  EXPECT_EQ(regularized_gamma_q(3, INFINITY), 0.0);
  EXPECT_THROW(regularized_gamma_q(0, 1), std::invalid_argument);
  EXPECT_THROW(regularized_gamma_q(1, -1), std::invalid_argument);
  EXPECT_TRUE(std::isnan(chi_square_p_value(NAN, 3)));
}

TEST(ChiSquare, SidakCorrection) {
  EXPECT_NEAR(sidak_alpha(0.01, 1), 0.01, 1e-17);
  EXPECT_NEAR(sidak_alpha(0.05, 2), 1 - std::sqrt(0.95), 1e-16);
  // The family-wise rate comes back: 1 - (1 - alpha_m)^m = alpha, also for a large family.
  for (std::size_t m : {3u, 100u, 1000000u}) {
    const double a = sidak_alpha(0.01, m);
    EXPECT_NEAR(-std::expm1(static_cast<double>(m) * std::log1p(-a)), 0.01, 1e-14) << m;
  }
  EXPECT_THROW(sidak_alpha(0.01, 0), std::invalid_argument);
}

TEST(ChiSquare, StatisticByHand) {
  const std::vector<double> observed = {12, 8}, expected = {10, 10};
  const ChiSquareResult r = chi_square_test(observed, expected);
  EXPECT_DOUBLE_EQ(r.statistic, 0.8);  // 4/10 + 4/10
  EXPECT_EQ(r.dof, 1);
  EXPECT_NEAR(r.p_value, std::erfc(std::sqrt(0.4)), 1e-15);
  EXPECT_EQ(r.observed_total, 20);
  EXPECT_EQ(r.expected_total, 20);
  // Expectations fixed in advance (not fitted to the total) keep all the degrees of freedom.
  EXPECT_EQ(chi_square_test(observed, expected, 0).dof, 2);
}

TEST(ChiSquare, PoolsSmallCellsSmallestFirst) {
  // Cells 1 and 3 (expected 1 and 4) pool into one cell of 5; the two cells of 10 stand alone.
  const std::vector<double> observed = {12, 2, 8, 3}, expected = {10, 1, 10, 4};
  const ChiSquareResult r = chi_square_test(observed, expected);
  ASSERT_EQ(r.cells.size(), 3u) << r.describe();
  EXPECT_EQ(r.cells[0].first_cell, 1u);
  EXPECT_EQ(r.cells[0].cell_count, 2u);
  EXPECT_EQ(r.cells[0].observed, 5);
  EXPECT_EQ(r.cells[0].expected, 5);
  EXPECT_DOUBLE_EQ(r.statistic, 0.8);  // the pool contributes 0
  EXPECT_EQ(r.dof, 2);
  EXPECT_NEAR(r.p_value, std::exp(-0.4), 1e-15);  // Q(1, x) = e^-x
}

TEST(ChiSquare, PoolsEveryCellToAtLeastFive) {
  // Ten cells of expectation 1.5: pools of 4 cells (6 >= 5) twice, then 2 left over (3 < 5) that
  // join the last pool.
  const std::vector<double> observed(10, 1.5), expected(10, 1.5);
  const ChiSquareResult r = chi_square_test(observed, expected);
  ASSERT_EQ(r.cells.size(), 2u) << r.describe();
  EXPECT_EQ(r.cells[0].cell_count, 4u);
  EXPECT_EQ(r.cells[1].cell_count, 6u);
  for (const PooledCell& c : r.cells) EXPECT_GE(c.expected, 5);
  // A cell at exactly the threshold is not merged.
  EXPECT_EQ(chi_square_test(std::vector<double>{5, 5}, std::vector<double>{5, 5}).cells.size(), 2u);
}

TEST(ChiSquare, TooFewSamplesLeaveNoDegreeOfFreedom) {
  const std::vector<double> observed = {3, 1, 0}, expected = {2, 1, 1};
  const ChiSquareResult r = chi_square_test(observed, expected);
  ASSERT_EQ(r.cells.size(), 1u);
  EXPECT_EQ(r.cells[0].cell_count, 3u);
  EXPECT_EQ(r.dof, 0);
  EXPECT_EQ(r.p_value, 1);
}

TEST(ChiSquare, SampleInZeroExpectationCellFails) {
  // The counts fit perfectly elsewhere (p = 1), yet one sample fell where none may.
  const std::vector<double> observed = {50, 1, 50}, expected = {50, 0, 50};
  const ChiSquareResult r = chi_square_test(observed, expected);
  ASSERT_EQ(r.impossible.size(), 1u);
  EXPECT_EQ(r.impossible[0].cell, 1u);
  EXPECT_EQ(r.impossible[0].observed, 1);
  EXPECT_GT(r.p_value, 0.5);
  EXPECT_FALSE(r.passes(0.01));
  EXPECT_NE(r.describe().find("expected count 0"), std::string::npos) << r.describe();
  // An empty cell of expectation 0 is simply not a cell.
  const ChiSquareResult clean = chi_square_test(std::vector<double>{50, 0, 50}, expected);
  EXPECT_TRUE(clean.impossible.empty());
  EXPECT_EQ(clean.cells.size(), 2u);
  EXPECT_TRUE(clean.passes(0.01));
}

TEST(ChiSquare, RejectsMalformedInput) {
  EXPECT_THROW(chi_square_test(std::vector<double>{1, 2}, std::vector<double>{1}), std::invalid_argument);
  EXPECT_THROW(chi_square_test(std::vector<double>{1}, std::vector<double>{-1}), std::invalid_argument);
  EXPECT_THROW(chi_square_test(std::vector<double>{NAN}, std::vector<double>{1}), std::invalid_argument);
}

TEST(ChiSquare, IndependentTablesAdd) {
  const ChiSquareResult parts[] = {
      chi_square_test(std::vector<double>{12, 8}, std::vector<double>{10, 10}),
      chi_square_test(std::vector<double>{30, 20, 1, 10}, std::vector<double>{20, 20, 0, 20}),
  };
  const ChiSquareResult sum = combine_independent(parts);
  EXPECT_DOUBLE_EQ(sum.statistic, parts[0].statistic + parts[1].statistic);
  EXPECT_EQ(sum.dof, 1 + 2);
  EXPECT_EQ(sum.p_value, chi_square_p_value(sum.statistic, sum.dof));
  EXPECT_EQ(sum.cells.size(), 5u);
  EXPECT_EQ(sum.cells[4].group, 1u);
  ASSERT_EQ(sum.impossible.size(), 1u);
  EXPECT_EQ(sum.impossible[0].group, 1u);
  EXPECT_EQ(sum.impossible[0].cell, 2u);
  EXPECT_FALSE(sum.passes(0.01));
}

TEST(ChiSquare, PValuesAreCalibratedUnderTheNullHypothesis) {
  // Hypothesis: for multinomial draws from the very probabilities tested, the helper's p-value is
  // uniform, pooling included (a third of the cells expect < 5). 400 tables, seed 7: the number
  // with p < 0.05 is Binomial(400, 0.05), mean 20, sd 4.4; [6, 38] holds it with probability
  // 0.9998 (tails 5e-5 + 7e-5), so a failure means the statistic, the pooling or the p-value is off.
  std::mt19937_64 rng(7);
  std::vector<double> probability;
  for (int i = 0; i < 60; ++i) probability.push_back(i < 20 ? 0.002 : 0.024);  // sums to 1
  const int samples = 1000;
  std::vector<double> expected;
  for (double p : probability) expected.push_back(p * samples);
  int rejected = 0;
  std::discrete_distribution<int> cell(probability.begin(), probability.end());
  for (int table = 0; table < 400; ++table) {
    std::vector<double> observed(probability.size(), 0);
    for (int s = 0; s < samples; ++s) observed[cell(rng)] += 1;
    rejected += chi_square_test(observed, expected).p_value < 0.05;
  }
  EXPECT_GE(rejected, 6);
  EXPECT_LE(rejected, 38);
}

}  // namespace
}  // namespace trs_test
