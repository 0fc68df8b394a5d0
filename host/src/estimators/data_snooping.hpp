// Internal to adjust() (bundle_adjustment.hpp): data snooping (thesis section 4.1.4, eqs 4.31
// and 4.52). Per image measurement the cofactors of its residual give its redundancy shares, its
// standardised residuals w and the probability of its residual vector under H0; the most
// improbable measurement beyond the critical value is removed and the network re-adjusted, one
// at a time. Once none is left, a point that lost a ray and kept two is removed whole when the
// data cannot tell which of its three rays was wrong.
#pragma once

#include <string>
#include <vector>

#include "estimators/adjustment_covariance.hpp"
#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/adjustment_problem.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "estimators/covariance.hpp"

namespace syncap::estimators {

// Each image term's redundancy shares q_vv / q_ll and standardised residuals (with `sigma0`, the
// one snooping standardises with) into `measurements`, and per measurement the natural logarithm
// of the probability under H0 of its residual vector (both coordinates together; 0 when the
// network does not control it) into `log_p`.
void test_residuals(const scene::Network& network, const std::vector<Term>& terms,
                    const std::vector<TermJacobian>& jacobians, const ArrowCofactors& cofactors,
                    double sigma0, std::vector<MeasurementResult>* measurements,
                    std::vector<double>* log_p);

// The standardised residuals of the accepted measurements that the network controls, for the
// goodness-of-fit test: the shape of their distribution, its scale being the variance test's.
std::vector<double> goodness_of_fit_sample(const BundleAdjustmentResult& result,
                                           const std::vector<MeasurementStatus>& status,
                                           bool snoop_with_a_posteriori_sigma0);

// ", N of them with the M points whose wrong ray could not be told", or nothing.
std::string ambiguous_note(const std::vector<RejectedMeasurement>& rejected);

// The rejections between the adjustments: they change the measurements' status and append to
// the rejected ones.
class DataSnooping {
 public:
  DataSnooping(const ResolvedNetwork& resolved, const AdjustmentParameters& parameters,
               std::vector<MeasurementStatus>* status, std::vector<RejectedMeasurement>* rejected)
      : resolved_(resolved), parameters_(parameters), status_(*status), rejected_(*rejected) {}

  // Removes the most improbable accepted measurement if its |w| is beyond the critical value (with
  // ResidualTest::reject_per_point, that of every point). True when any went.
  bool reject_worst_blunder(const std::vector<double>& log_p);
  // Removes the points whose wrong ray the data cannot tell. True when any went.
  bool reject_ambiguous_points(const std::vector<double>& log_p, double sigma0);

 private:
  void reject(size_t m, double w, bool ambiguous = false);
  double pair_square_sum(size_t a, size_t b) const;

  const ResolvedNetwork& resolved_;
  const AdjustmentParameters& parameters_;
  std::vector<MeasurementStatus>& status_;
  std::vector<RejectedMeasurement>& rejected_;
};

}  // namespace syncap::estimators
