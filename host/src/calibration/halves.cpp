#include "calibration/halves.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "calibration/calibrate.hpp"
#include "estimators/statistical_tests.hpp"
#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

Observations with_frames(const Observations& all, const std::set<int64_t>& frames) {
  Observations out = all;
  std::erase_if(out.frames, [&](const auto& item) { return !frames.count(item.first); });
  return out;
}

// The spread of the cameras' centres: their RMS distance from their centroid.
double spread_mm(const std::vector<sensor::CameraModel>& cameras) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const sensor::CameraModel& c : cameras) centroid += c.projection_centre();
  centroid /= static_cast<double>(cameras.size());
  double sum = 0;
  for (const sensor::CameraModel& c : cameras) {
    sum += (c.projection_centre() - centroid).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(cameras.size()));
}

// The similarity (scale s, rotation r, translation t) that fits `from`'s centres onto `onto`'s.
Eigen::Matrix4d centre_similarity(const std::vector<sensor::CameraModel>& onto,
                                  const std::vector<sensor::CameraModel>& from) {
  Eigen::Matrix3Xd pa(3, onto.size()), pb(3, from.size());
  for (size_t i = 0; i < onto.size(); ++i) {
    pa.col(static_cast<Eigen::Index>(i)) = onto[i].projection_centre();
    pb.col(static_cast<Eigen::Index>(i)) = from[i].projection_centre();
  }
  return Eigen::umeyama(pb, pa, true);
}

double scale_of(const Eigen::Matrix4d& similarity) {
  return std::cbrt(similarity.topLeftCorner<3, 3>().determinant());
}

// A kind of value (c of every camera, the centres, ...) whose halves disagree by more than the
// chi-square bound of their sigmas at this level; others add nothing (one chance |z| of 3 in a
// calibration of 20 values is no systematic error).
constexpr double kExcessLevel = 0.99;

// Per camera, the whole's share of the excess: 1/4 (R - 1) (sigma_a^2 + sigma_b^2) with R the
// mean of (a - b)^2 / (sigma_a^2 + sigma_b^2) over the cameras (the kind's Birge ratio), when
// the kind disagrees significantly; else zeros. Cameras without both sigmas are left out.
std::vector<double> excess(const std::vector<double>& difference2,
                           const std::vector<double>& variance) {
  std::vector<double> out(difference2.size(), 0.0);
  double chi2 = 0;
  int n = 0;
  for (size_t i = 0; i < difference2.size(); ++i) {
    if (!(variance[i] > 0)) continue;
    chi2 += difference2[i] / variance[i];
    ++n;
  }
  if (n == 0 || chi2 <= estimators::chi_square_quantile(kExcessLevel, n)) return out;
  const double ratio = chi2 / n;
  for (size_t i = 0; i < out.size(); ++i) {
    if (variance[i] > 0) out[i] = 0.25 * (ratio - 1.0) * variance[i];
  }
  return out;
}

}  // namespace

HalvesExcess halves_excess(const HalvesAgreement& halves,
                           const std::vector<sensor::CameraModel>& whole) {
  HalvesExcess out;
  const size_t cameras = whole.size();
  if (!halves.compared || halves.a.size() != cameras || cameras < 3) return out;
  const Eigen::Matrix4d b_onto_a = centre_similarity(halves.a, halves.b);
  const double to_whole = scale_of(centre_similarity(whole, halves.a));
  const double b_scale = scale_of(b_onto_a);
  out.interior_variance.assign(cameras, std::array<double, 10>{});
  for (size_t k = 0; k < sensor::InteriorBlock::kSize; ++k) {
    std::vector<double> d2(cameras, 0.0), variance(cameras, 0.0);
    for (size_t i = 0; i < cameras; ++i) {
      const sensor::CameraModel &a = halves.a[i], &b = halves.b[i];
      if (!a.std_devs || !b.std_devs) continue;
      const double sa = sensor::interior_block(a.std_devs->interior)[k];
      const double sb = sensor::interior_block(b.std_devs->interior)[k];
      if (!(sa > 0) || !(sb > 0)) continue;
      const double d =
          sensor::interior_block(a.interior)[k] - sensor::interior_block(b.interior)[k];
      d2[i] = d * d;
      variance[i] = sa * sa + sb * sb;
    }
    const std::vector<double> e = excess(d2, variance);
    for (size_t i = 0; i < cameras; ++i) out.interior_variance[i][k] = e[i];
  }
  // The centres: |a - b|^2 against the sum of their variances, shared over the three axes.
  std::vector<double> d2(cameras, 0.0), variance(cameras, 0.0);
  auto trace = [](const sensor::ExteriorOrientation& s) {
    return s.X0 * s.X0 + s.Y0 * s.Y0 + s.Z0 * s.Z0;
  };
  for (size_t i = 0; i < cameras; ++i) {
    const sensor::CameraModel &a = halves.a[i], &b = halves.b[i];
    if (!a.std_devs || !b.std_devs) continue;
    const Eigen::Vector3d moved =
        b_onto_a.topLeftCorner<3, 3>() * b.projection_centre() + b_onto_a.topRightCorner<3, 1>();
    d2[i] = (a.projection_centre() - moved).squaredNorm();
    variance[i] = trace(a.std_devs->exterior) + b_scale * b_scale * trace(b.std_devs->exterior);
  }
  for (double e : excess(d2, variance))
    out.centre_variance.push_back(to_whole * to_whole * e / 3.0);
  return out;
}

double centres_apart_mm(const std::vector<sensor::CameraModel>& a,
                        const std::vector<sensor::CameraModel>& b) {
  Eigen::Matrix3Xd pa(3, a.size()), pb(3, b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    pa.col(static_cast<Eigen::Index>(i)) = a[i].projection_centre();
    pb.col(static_cast<Eigen::Index>(i)) = b[i].projection_centre();
  }
  const Eigen::Matrix4d t = Eigen::umeyama(pb, pa, true);
  const Eigen::Matrix3Xd moved =
      (t.topLeftCorner<3, 3>() * pb).colwise() + t.topRightCorner<3, 1>();
  return std::sqrt((moved - pa).colwise().squaredNorm().mean());
}

HalvesAgreement compare_halves(const Observations& observations, const std::vector<int64_t>& frames,
                               const CalibrationOptions& model,
                               const std::vector<sensor::InteriorOrientation>& start) {
  HalvesAgreement out;
  // Contiguous halves: a wand identified by the continuity of its ends needs the frames in a row.
  std::set<int64_t> first, second;
  for (size_t i = 0; i < frames.size(); ++i)
    (2 * i < frames.size() ? first : second).insert(frames[i]);
  CalibrationOptions half = model;
  half.start_fields_of_view_deg.clear();
  half.start_interiors = start;
  half.select_model = false;
  half.check_point_share = 0;
  half.compare_halves = false;
  half.bootstrap_samples = 0;
  half.max_frames = 0;
  half.progress = nullptr;
  CalibrationResult a, b;
  try {
    a = calibrate(with_frames(observations, first), half);
    b = calibrate(with_frames(observations, second), half);
  } catch (const std::exception& e) {
    out.failure = e.what();
    out.text = std::string("the halves could not both be calibrated: ") + e.what();
    return out;
  }
  if (!a.adjustment.converged || !b.adjustment.converged || a.cameras.size() != b.cameras.size()) {
    out.failure = "a half did not converge";
    out.text = "the halves could not both be calibrated: a half did not converge";
    return out;
  }
  out.compared = true;
  out.a = a.cameras;
  out.b = b.cameras;
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    const double ca = a.cameras[i].interior.c, cb = b.cameras[i].interior.c;
    const double sa = a.cameras[i].std_devs ? a.cameras[i].std_devs->interior.c : 0.0;
    const double sb = b.cameras[i].std_devs ? b.cameras[i].std_devs->interior.c : 0.0;
    const double z = (ca - cb) / std::sqrt(std::max(sa * sa + sb * sb, 1e-30));
    out.camera_ids.push_back(a.cameras[i].id);
    out.c_a_mm.push_back(ca);
    out.c_b_mm.push_back(cb);
    out.z.push_back(z);
    out.worst_z = std::max(out.worst_z, std::abs(z));
  }
  out.centres_rms_mm = centres_apart_mm(a.cameras, b.cameras);
  out.centres_spread_mm = spread_mm(a.cameras);
  std::string cs;
  for (size_t i = 0; i < out.z.size(); ++i) {
    cs += util::printf_string("%scamera %d %.4f/%.4f mm (z %.1f)", i ? ", " : "", out.camera_ids[i],
                              out.c_a_mm[i], out.c_b_mm[i], out.z[i]);
  }
  out.text = util::printf_string(
      "first %zu and last %zu frames: c %s; centres %.3g units apart after a similarity fit (%.2f "
      "%% of "
      "their spread)",
      first.size(), second.size(), cs.c_str(), out.centres_rms_mm,
      100.0 * out.centres_rms_mm / std::max(out.centres_spread_mm, 1e-30));
  return out;
}

}  // namespace syncap::calibration
