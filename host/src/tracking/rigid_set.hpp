// Rigid marker sets: markers fixed to one body (the calibration wand, a tool, a head band) at
// known positions in the set's own frame. Each frame the set is found among the tracked points by
// its inter-marker distances, and its 6-DoF pose fitted to them (Kabsch / Umeyama without scale).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tracking/marker_tracker.hpp"

namespace syncap::tracking {

struct RigidMarker {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  // in the set's frame
};

struct RigidSet {
  std::string name;
  std::vector<RigidMarker> markers;  // at least 3
  // How far each measured inter-marker distance, and the fit's RMS, may be off [mm].
  double tolerance_mm = 3.0;
};

// The set's pose in one frame: world = rotation * set + translation.
struct RigidSetPose {
  bool found = false;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation_mm = Eigen::Vector3d::Zero();
  double rms_mm = 0;  // the fit's RMS distance of the markers to their points
  // All markers on one line (a wand): the roll about the line is unknown, and `rotation` is the
  // smallest rotation that takes the set's line to the measured one.
  bool collinear = false;
  std::vector<TrackId> ids;  // ids[m]: the track of marker m
  std::vector<int> points;   // points[m]: its index among the frame's points
};

struct RigidFit {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rms = 0;
};

// The rotation and translation that take `model` nearest to `measured` (least squares; same
// count, >= 2 points). `collinear`: the model's points lie on a line (see RigidSetPose).
RigidFit fit_rigid(const std::vector<Eigen::Vector3d>& model,
                   const std::vector<Eigen::Vector3d>& measured, bool collinear);

// Whether the markers lie on one line (within 1 % of the set's extent).
bool is_collinear(const RigidSet& set);

class RigidSetFinder {
 public:
  explicit RigidSetFinder(std::vector<RigidSet> sets);

  // The pose of each set (found or not) among the frame's points that have a track. A set found
  // in the previous frame is first tried with the same tracks; otherwise, or when they no longer
  // fit, every assignment of points to its markers whose distances agree is fitted and the one
  // with the smallest RMS kept. Sets never share a point.
  const std::vector<RigidSetPose>& find(std::span<const PointObservation> points,
                                        std::span<const TrackId> ids);

  const std::vector<RigidSet>& sets() const { return sets_; }

 private:
  std::vector<RigidSet> sets_;
  std::vector<char> collinear_;
  std::vector<RigidSetPose> poses_;
  std::vector<char> used_;  // per point: taken by a set this frame

  bool try_previous(std::size_t set, std::span<const PointObservation> points,
                    std::span<const TrackId> ids);
  bool search(std::size_t set, std::span<const PointObservation> points,
              std::span<const TrackId> ids);
  void extend(std::size_t set, std::span<const PointObservation> points,
              std::span<const TrackId> ids, std::vector<int>& chosen, std::vector<int>& best,
              double& best_rms);
  bool accept(std::size_t set, const std::vector<int>& chosen,
              std::span<const PointObservation> points, std::span<const TrackId> ids);
};

}  // namespace syncap::tracking
