#include "calibration/halves.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "calibration/calibrate.hpp"
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

}  // namespace

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
