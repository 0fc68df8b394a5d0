// A frame group on its way through the host's stages: what the grouper handed out and what each
// stage added (docs/design/architecture.md, "The host's pipeline").
#pragma once

#include <Eigen/Core>
#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "grouping/frame_grouper.hpp"
#include "syncap/proto/clock.hpp"

namespace syncap::pipeline {

// One 3D marker of a frame.
struct Marker3d {
  int id = -1;  // persistent trajectory id once tracked; -1 before
  Eigen::Vector3d position = Eigen::Vector3d::Zero();    // mm, the calibration's frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // mm^2
  double residual_px = 0;                                // RMS of its rays' errors
  std::vector<int> camera_ids;                           // the cameras that saw it, ascending
  bool predicted = false;  // not seen this frame: the tracker's prediction
  bool two_cameras_only() const { return camera_ids.size() == 2; }
};

// The 6-DoF pose of a rigid marker set in one frame (tracking::RigidSetPose, named).
struct RigidBody {
  std::string name;
  bool found = false;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // world = rotation * set + translation
  Eigen::Vector3d translation_mm = Eigen::Vector3d::Zero();
  double rms_mm = 0;
  bool collinear = false;       // a wand: the roll about its line is unknown
  std::vector<int> marker_ids;  // the trajectory id of each of its markers (-1: not found)
};

// The visual hull of one frame (reconstruction::HullStage): what it measures. The mesh itself goes
// to files (--hull-meshes), not down the pipeline.
struct HullSummary {
  int flags = 0;    // hull_frame_t::FLAG_*, ORed
  int cameras = 0;  // silhouettes that made the hull
  std::size_t vertices = 0;
  std::size_t faces = 0;
  double volume_mm3 = 0;
  double area_mm2 = 0;
  Eigen::Vector3d min_mm = Eigen::Vector3d::Zero();  // bounding box, the calibration's frame
  Eigen::Vector3d max_mm = Eigen::Vector3d::Zero();
  double hull_us = 0;  // building it (wall time)
  // Camera id -> IoU of the hull's reprojection against that camera's silhouette, when asked.
  std::map<int, double> view_iou;
  std::string error;  // why there is no hull (FLAG_FAILED)
  // Points spread evenly over the mesh's surface, when the stage is asked for them (the body
  // fit's input: HullProducts::surface_samples).
  std::vector<Eigen::Vector3d> surface_mm;
  // The mesh's triangles (corners, mm), when the stage is asked for them (the surface stage's
  // input: HullProducts::triangles); shared, read only, so a stage on another thread
  // can keep them.
  std::shared_ptr<const std::vector<std::array<Eigen::Vector3d, 3>>> triangles;
};

// The articulated body fitted to one frame's hull (reconstruction::BodyFitStage,
// docs/design/body-fit.md).
struct BodyFitSummary {
  int flags = 0;                   // body_frame_t::FLAG_*, ORed
  std::vector<double> parameters;  // the pose (fitting::PoseVector); empty without a fit
  // The joints' centres [mm] in the calibration's frame, named (H-Anim), in the order of
  // body_frame_t's joint_mm (the root, then fitting::kFittedJoints); empty without a fit.
  std::vector<std::string> joint_names;
  std::vector<Eigen::Vector3d> joints_mm;
  double rms_mm = 0;    // the hull points' distances to the body's surface, RMS
  int points = 0;       // hull surface points given to the fit
  int points_kept = 0;  // of them, within the fit's last gate
  double fit_us = 0;    // the fit, and the automatic start when there was one (wall time)
  // The fit's precision (fitting::PosePrecision); the vectors empty when it has none.
  double sigma0 = 0;
  std::vector<double> parameter_sigmas;  // per parameter [mm, rad]
  std::vector<double> joint_sigmas_mm;   // per joint, in joint_names' order
};

struct FrameWork {
  grouping::FrameGroup group;
  // When the grouper handed the group out: the host's time for it starts here.
  std::chrono::steady_clock::time_point ready;
  // The worker thread's CPU time when the first stage started on the group [us, thread_cpu_us].
  double cpu_start_us = 0;
  std::vector<Marker3d> markers;
  std::vector<RigidBody> rigid_bodies;  // one per set of the rigid set stage, found or not
  std::optional<HullSummary> hull;      // the hull stage ran on a group with silhouettes
  std::optional<BodyFitSummary> body;   // the body fit stage ran on a group with a hull
};

// The calling thread's CPU time [us] (CLOCK_THREAD_CPUTIME_ID): what a stage cost the host,
// without the waits for a CPU that the wall time holds on a loaded machine.
inline double thread_cpu_us() {
  return static_cast<double>(proto::clock_now_ns(CLOCK_THREAD_CPUTIME_ID)) * 1e-3;
}

// A step of the host's per-frame work. Stages run in order on the pipeline's worker thread, one
// frame at a time; a stage keeps its own state across frames (a tracker does).
class Stage {
 public:
  virtual ~Stage() = default;
  virtual const char* name() const = 0;
  virtual void process(FrameWork& work) = 0;
  // After the last frame (flush files, print a summary line).
  virtual void finish() {}
};

}  // namespace syncap::pipeline
