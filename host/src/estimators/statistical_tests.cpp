#include "estimators/statistical_tests.hpp"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace syncap::estimators {
namespace {

// Every class of the goodness-of-fit test should expect at least this many residuals, the usual
// condition for the chi-square approximation of y.
constexpr double kMinExpectedPerBin = 5.0;

double standard_normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// The Kolmogorov distribution's survival function Q(lambda) = 2 sum (-1)^(j-1) exp(-2 j^2 l^2).
double kolmogorov_survival(double lambda) {
  if (lambda < 0.2) return 1.0;  // the series converges slowly there, and Q is 1 to 1e-10
  double sum = 0.0;
  for (int j = 1; j <= 100; ++j) {
    const double term = std::exp(-2.0 * j * j * lambda * lambda);
    sum += (j % 2 == 1 ? term : -term);
    if (term < 1e-12) break;
  }
  return std::clamp(2.0 * sum, 0.0, 1.0);
}

void require_probability(double p, const char* what) {
  if (!(p > 0.0 && p < 1.0)) {
    throw std::invalid_argument(std::string(what) + ": probability must be in (0, 1), got " +
                                std::to_string(p));
  }
}

}  // namespace

double chi_square_quantile(double p, double dof) {
  require_probability(p, "chi_square_quantile");
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(dof), p);
}

double normal_quantile(double p) {
  require_probability(p, "normal_quantile");
  return boost::math::quantile(boost::math::normal_distribution<double>(0.0, 1.0), p);
}

VarianceFactorTest test_variance_factor(double variance_factor, long redundancy, double alpha) {
  require_probability(alpha, "variance factor test: alpha");
  VarianceFactorTest test;
  test.variance_factor = variance_factor;
  test.redundancy = redundancy;
  test.alpha = alpha;
  if (redundancy <= 0) return test;  // no redundancy: nothing can be tested, and it fails
  const double r = static_cast<double>(redundancy);
  test.lower = chi_square_quantile(alpha / 2.0, r) / r;
  test.upper = chi_square_quantile(1.0 - alpha / 2.0, r) / r;
  test.passed = variance_factor >= test.lower && variance_factor <= test.upper;
  return test;
}

GoodnessOfFitTest test_goodness_of_fit(const std::vector<double>& standardised_residuals,
                                       double alpha) {
  require_probability(alpha, "goodness-of-fit test: alpha");
  GoodnessOfFitTest test;
  test.alpha = alpha;
  test.samples = static_cast<long>(standardised_residuals.size());
  const double n = static_cast<double>(test.samples);
  if (test.samples < 10) {
    test.passed = true;
    return test;
  }

  // Eqs 4.47-4.48 over classes of equal probability 1/m: class i holds w with
  // Phi(w) in [i/m, (i+1)/m), so e_i = n/m.
  const int mann_wald = static_cast<int>(std::ceil(2.0 * std::pow(n, 0.4)));
  test.bins = std::clamp(std::min(mann_wald, static_cast<int>(n / kMinExpectedPerBin)), 5, 100);
  std::vector<long> counts(test.bins, 0);
  std::vector<double> sorted = standardised_residuals;
  std::sort(sorted.begin(), sorted.end());
  for (double w : sorted) {
    const int bin = static_cast<int>(standard_normal_cdf(w) * test.bins);
    ++counts[std::clamp(bin, 0, test.bins - 1)];
  }
  const double expected = n / test.bins;
  for (long a : counts) test.statistic += (a - expected) * (a - expected) / expected;
  test.critical = chi_square_quantile(1.0 - alpha, test.bins - 1);
  test.passed = test.statistic <= test.critical;

  // Kolmogorov-Smirnov: the largest gap between the empirical and the normal distribution.
  for (size_t i = 0; i < sorted.size(); ++i) {
    const double f = standard_normal_cdf(sorted[i]);
    test.ks_distance = std::max({test.ks_distance, (i + 1) / n - f, f - i / n});
  }
  const double root_n = std::sqrt(n);
  test.ks_p_value = kolmogorov_survival((root_n + 0.12 + 0.11 / root_n) * test.ks_distance);
  return test;
}

double snooping_critical_value(double alpha) {
  require_probability(alpha, "snooping critical value: alpha");
  return normal_quantile(1.0 - alpha / 2.0);
}

}  // namespace syncap::estimators
