// The post-adjustment tests of thesis section 4.1.4 (lines 2930-3033): the two-tailed chi-square
// test of the a posteriori variance factor (eq 4.45), the chi-square goodness-of-fit test of the
// standardised residuals against N(0, 1) (eqs 4.46-4.49, with a Kolmogorov-Smirnov statistic
// beside it), and the critical value of data snooping (eq 4.52). Pure functions of numbers; the
// bundle adjustment (bundle_adjustment.hpp) feeds them.
#pragma once

#include <vector>

namespace syncap::estimators {

// Eq 4.45: H0 sigma0^2 (a priori, 1) = sigma0_hat^2 is kept when
// chi2(alpha/2, r) / r <= sigma0_hat^2 <= chi2(1 - alpha/2, r) / r.
struct VarianceFactorTest {
  double variance_factor = 0.0;  // sigma0_hat^2 = v^T P v / r
  long redundancy = 0;           // r
  double alpha = 0.05;
  double lower = 0.0;  // acceptance interval of the variance factor
  double upper = 0.0;
  bool passed = false;
};

VarianceFactorTest test_variance_factor(double variance_factor, long redundancy, double alpha);

// Eqs 4.47-4.49: the standardised residuals binned into `bins` classes of equal probability
// under N(0, 1); y = sum (a_i - e_i)^2 / e_i is kept when y <= chi2(1 - alpha, bins - 1). The
// Kolmogorov-Smirnov distance to N(0, 1) and its asymptotic p-value are reported beside it.
struct GoodnessOfFitTest {
  long samples = 0;
  int bins = 0;
  double alpha = 0.05;
  double statistic = 0.0;  // y
  double critical = 0.0;   // chi2(1 - alpha, bins - 1)
  bool passed = false;
  double ks_distance = 0.0;  // sup |F_n(w) - Phi(w)|
  double ks_p_value = 1.0;   // asymptotic (Kolmogorov distribution, Stephens' correction)
};

// The bin count: the Mann-Wald rule 2 n^(2/5) (equal-probability classes), clamped to [5, 100],
// fewer when n is small so that every class expects at least 5 residuals. n < 10 gives a test with
// bins = 0 that passes (too few residuals to judge).
GoodnessOfFitTest test_goodness_of_fit(const std::vector<double>& standardised_residuals,
                                       double alpha);

// Eq 4.52: the two-tailed critical value n(1 - alpha/2) of a standardised residual (3.29 for
// alpha = 0.001, Baarda's usual data-snooping level).
double snooping_critical_value(double alpha);

// Quantiles of the distributions above (Boost.Math): the p-quantile of chi-square with `dof`
// degrees of freedom and of the standard normal.
double chi_square_quantile(double p, double dof);
double normal_quantile(double p);

}  // namespace syncap::estimators
