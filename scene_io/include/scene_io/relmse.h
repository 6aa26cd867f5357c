#pragma once
// relMSE, the tools' noise figure: the mean over values of (x - r)^2 / (r^2 + kRelmseGuard), x a
// render's value and r the reference's.

namespace trs {

/// Added to r^2 so that dark pixels, where any error is large next to the value, do not dominate.
/// trs-imgdiff prints it; the Python tools' trs_measure.GUARD is tested against that.
inline constexpr double kRelmseGuard = 0.01;

/// One value's term of relMSE.
inline double relative_squared_error(double test, double reference) {
  const double e = test - reference;
  return e * e / (reference * reference + kRelmseGuard);
}

}  // namespace trs
