#include "tracking/rigid_set.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

namespace syncap::tracking {
namespace {

using Eigen::Vector3d;

Vector3d centroid(const std::vector<Vector3d>& points) {
  Vector3d sum = Vector3d::Zero();
  for (const Vector3d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// The direction of the least-squares line through the points, pointing from the first point
// towards the last (so that the model's and the measurement's agree).
Vector3d line_direction(const std::vector<Vector3d>& points) {
  const Vector3d c = centroid(points);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vector3d& p : points) scatter += (p - c) * (p - c).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(scatter, Eigen::ComputeFullU);
  Vector3d axis = svd.matrixU().col(0);
  if (axis.dot(points.back() - points.front()) < 0) axis = -axis;
  return axis;
}

double rms_distance(const RigidFit& fit, const std::vector<Vector3d>& model,
                    const std::vector<Vector3d>& measured) {
  double sum = 0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    sum += (fit.rotation * model[i] + fit.translation - measured[i]).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(model.size()));
}

// Whether `candidate`, as marker chosen.size() of the set, is at the set's distances from the
// points chosen for the markers before it.
bool distances_agree(const RigidSet& set, const std::vector<int>& chosen, const Vector3d& candidate,
                     std::span<const PointObservation> points) {
  const Vector3d& model = set.markers[chosen.size()].position_mm;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const double measured = (candidate - points[chosen[i]].position_mm).norm();
    const double expected = (model - set.markers[i].position_mm).norm();
    if (std::abs(measured - expected) > set.tolerance_mm) return false;
  }
  return true;
}

}  // namespace

RigidFit fit_rigid(const std::vector<Vector3d>& model, const std::vector<Vector3d>& measured,
                   bool collinear) {
  RigidFit fit;
  if (collinear) {
    fit.rotation =
        Eigen::Quaterniond::FromTwoVectors(line_direction(model), line_direction(measured))
            .toRotationMatrix();
  } else {
    Eigen::Matrix3Xd from(3, model.size()), to(3, measured.size());
    for (std::size_t i = 0; i < model.size(); ++i) {
      from.col(i) = model[i];
      to.col(i) = measured[i];
    }
    fit.rotation = Eigen::umeyama(from, to, false).topLeftCorner<3, 3>();
  }
  fit.translation = centroid(measured) - fit.rotation * centroid(model);
  fit.rms = rms_distance(fit, model, measured);
  return fit;
}

bool is_collinear(const RigidSet& set) {
  std::vector<Vector3d> points;
  for (const RigidMarker& m : set.markers) points.push_back(m.position_mm);
  const Vector3d c = centroid(points);
  const Vector3d axis = line_direction(points);
  double extent = 0, off_line = 0;
  for (const Vector3d& p : points) {
    const Vector3d d = p - c;
    extent = std::max(extent, d.norm());
    off_line = std::max(off_line, (d - d.dot(axis) * axis).norm());
  }
  return off_line <= 0.01 * extent;
}

RigidSetFinder::RigidSetFinder(std::vector<RigidSet> sets)
    : sets_(std::move(sets)), poses_(sets_.size()) {
  for (const RigidSet& s : sets_) collinear_.push_back(is_collinear(s) ? 1 : 0);
}

const std::vector<RigidSetPose>& RigidSetFinder::find(std::span<const PointObservation> points,
                                                      std::span<const TrackId> ids) {
  used_.assign(points.size(), 0);
  for (std::size_t s = 0; s < sets_.size(); ++s) {
    const bool was_found = poses_[s].found;
    poses_[s].found = false;
    if (was_found && try_previous(s, points, ids)) continue;
    search(s, points, ids);
  }
  return poses_;
}

// The tracks that made the set last frame, if all still have a point and still fit.
bool RigidSetFinder::try_previous(std::size_t set, std::span<const PointObservation> points,
                                  std::span<const TrackId> ids) {
  std::vector<int> chosen;
  for (TrackId id : poses_[set].ids) {
    const auto at = std::find(ids.begin(), ids.end(), id);
    if (at == ids.end() || used_[at - ids.begin()]) return false;
    chosen.push_back(static_cast<int>(at - ids.begin()));
  }
  return accept(set, chosen, points, ids);
}

bool RigidSetFinder::search(std::size_t set, std::span<const PointObservation> points,
                            std::span<const TrackId> ids) {
  std::vector<int> chosen, best;
  double best_rms = std::numeric_limits<double>::infinity();
  extend(set, points, ids, chosen, best, best_rms);
  return !best.empty() && accept(set, best, points, ids);
}

// Depth first: marker chosen.size() takes each free point whose distances to the points chosen
// so far match the set's within the tolerance; complete choices are fitted, the best kept.
void RigidSetFinder::extend(std::size_t set, std::span<const PointObservation> points,
                            std::span<const TrackId> ids, std::vector<int>& chosen,
                            std::vector<int>& best, double& best_rms) {
  const RigidSet& s = sets_[set];
  const std::size_t m = chosen.size();
  if (m == s.markers.size()) {
    std::vector<Vector3d> model, measured;
    for (std::size_t i = 0; i < m; ++i) {
      model.push_back(s.markers[i].position_mm);
      measured.push_back(points[chosen[i]].position_mm);
    }
    const double rms = fit_rigid(model, measured, collinear_[set]).rms;
    if (rms < best_rms) {
      best_rms = rms;
      best = chosen;
    }
    return;
  }
  for (int p = 0; p < static_cast<int>(points.size()); ++p) {
    if (ids[p] == kNoTrack || used_[p] ||
        std::find(chosen.begin(), chosen.end(), p) != chosen.end())
      continue;
    if (!distances_agree(s, chosen, points[p].position_mm, points)) continue;
    chosen.push_back(p);
    extend(set, points, ids, chosen, best, best_rms);
    chosen.pop_back();
  }
}

bool RigidSetFinder::accept(std::size_t set, const std::vector<int>& chosen,
                            std::span<const PointObservation> points,
                            std::span<const TrackId> ids) {
  const RigidSet& s = sets_[set];
  std::vector<Vector3d> model, measured;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    model.push_back(s.markers[i].position_mm);
    measured.push_back(points[chosen[i]].position_mm);
  }
  const RigidFit fit = fit_rigid(model, measured, collinear_[set]);
  if (fit.rms > s.tolerance_mm) return false;
  RigidSetPose& pose = poses_[set];
  pose = {true, fit.rotation, fit.translation, fit.rms, collinear_[set] != 0, {}, chosen};
  for (int p : chosen) {
    pose.ids.push_back(ids[p]);
    used_[p] = 1;
  }
  return true;
}

}  // namespace syncap::tracking
