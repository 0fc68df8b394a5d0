// Internal to adjust() (bundle_adjustment.hpp): the datum of the adjustment. Fixed and observed
// exterior or object point values define it when there are any; otherwise the network is free:
// it is solved with minimal constraints (the station with the most measurements holds its
// exterior orientation and, without distances, one coordinate of another station's centre the
// scale), and its cofactors are S-transformed to the inner-constraint datum of the object points.
// docs/design/calibration.md, "Bundle adjustment".
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "estimators/covariance.hpp"

namespace syncap::estimators {

struct DatumChoice {
  Datum datum = Datum::kGivenParameters;
  // Per station, the exterior values held although free: a free network's minimal constraints.
  std::vector<std::array<bool, kExteriorSize>> held;
};

// The directions of the null space of a free network's normal matrix: translations, rotations
// about the points' centroid and, without distances, the scale, as changes of every exterior
// orientation and object point (interior orientations do not change).
struct DatumDefect {
  int size = 0;
  Eigen::MatrixXd camera;               // rows: camera parameters
  std::vector<Eigen::MatrixXd> groups;  // rows: group values
};

DatumDefect datum_defect(const scene::Network& network, const AdjustmentParameters& parameters);

// The datum of the network at its approximate values; `messages` get how it is defined.
DatumChoice choose_datum(const ResolvedNetwork& resolved, const AdjustmentParameters& parameters,
                         std::vector<std::string>* messages);

// Q' = S Q S^T, the cofactors of the free network's solution in the inner-constraint datum.
void s_transform(const scene::Network& network, const AdjustmentParameters& parameters,
                 ArrowCofactors* q);

}  // namespace syncap::estimators
