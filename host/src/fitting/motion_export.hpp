// A fitted motion as the exports take it (docs/design/body-fit.md, "Exports"): the BVH skeleton of
// the root and the fitted joints with the subject's offsets and, per frame, their rotations
// (io/bvh_writer.hpp); the joints' centres as trajectories for C3D and TRC
// (tracking/marker_trajectories.hpp). Every joint between two fitted ones keeps its rest
// orientation relative to its parent, so the BVH chain from one fitted joint to the next is one
// rigid offset: the BVH figure's joints are exactly the fitted figure's.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fitting/surface_fit.hpp"
#include "io/bvh_writer.hpp"
#include "tracking/marker_trajectories.hpp"

namespace syncap::fitting {

// The BVH joints: the skeleton's root, then kFittedJoints in order, each under its nearest fitted
// ancestor (or the root), with the rest offsets; a joint without fitted descendants ends at its
// farthest descendant node (a finger tip, a toe, the skull's top).
std::vector<io::BvhJoint> bvh_joints(const PoseParameters& parameters);

// The motion of `frames` at `rate_hz`; a frame without a pose (nullopt) repeats the last one
// before it (the first pose for leading gaps); throws std::invalid_argument when no frame has a
// pose.
io::BvhMotion bvh_motion(const PoseParameters& parameters,
                         std::span<const std::optional<PoseVector>> frames, double rate_hz);

// The centres of bvh_joints' joints per frame, labelled with their names; a frame without a pose
// is a gap. `first_frame` is the frame number of frames[0].
tracking::MarkerTrajectories joint_trajectories(const PoseParameters& parameters,
                                                std::span<const std::optional<PoseVector>> frames,
                                                double rate_hz, int64_t first_frame);

}  // namespace syncap::fitting
