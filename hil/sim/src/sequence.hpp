// What is in front of the cameras at each frame of a scenario: the phase, the wand targets or
// LED (with their exposure paths for motion blur), the person's ellipsoids, the lamp gain.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mocap_source.hpp"
#include "motion.hpp"
#include "render.hpp"
#include "scenario.hpp"

namespace syncap::sim {

// The person at time t: joint positions and either one ellipsoid per segment (with its H-Anim
// name) or the skinned human's posed mesh, mm, Z up.
struct BodyFrame {
  std::vector<std::pair<std::string, Eigen::Vector3d>> joints;
  std::vector<Ellipsoid> ellipsoids;
  std::vector<std::string> segments;  // the ellipsoids' names
  Mesh mesh;                          // person.model: mesh
  std::string subject;                // the mesh's subject

  bool empty() const { return joints.empty(); }
};

// The centre of `marker` on `body` (its segment's ellipsoid), or nothing when the body has no
// segment of that name.
std::optional<Eigen::Vector3d> marker_centre(const BodyFrame& body, const MarkerSpec& marker,
                                             double radius_mm);
using BodySource = std::function<BodyFrame(double t_s)>;
// Opens the motion of a person phase (its BVH); throws with file and line on a broken file.
using BodySourceFactory = std::function<BodySource(const PersonSpec&, const Scenario&)>;
// Opens the trajectories of a mocap phase (mocap_source.hpp).
using MocapSourceFactory =
    std::function<std::shared_ptr<const MocapSource>(const PhaseSpec&, const Scenario&)>;

struct FrameState {
  int frame = 0;
  int phase_index = 0;
  const PhaseSpec* phase = nullptr;
  double time_s = 0;        // since the first frame
  double phase_time_s = 0;  // since the phase's first frame
  bool led_on = false;
  FrameContent content;
  BodyFrame body;  // person phases only
  // The target number of each of content.spheres; empty: 0, 1, ... (a mocap phase leaves out the
  // absent markers, the others keep their numbers).
  std::vector<int> target_ids;
  // Mocap phases: the name of every target number (the file's markers, then the extra ones).
  const std::vector<std::string>* target_names = nullptr;
};

class Sequence {
 public:
  Sequence(const Scenario& scenario, const BodySourceFactory& bodies,
           const MocapSourceFactory& mocaps = open_mocap);

  int frames() const { return scenario_.total_frames(); }
  FrameState at(int frame);

 private:
  Sphere sphere_at(WaypointPath& path, double t, double offset_mm, double radius_mm,
                   double brightness, double exposure_ms) const;
  double gain_at(int frame) const;
  void add_mocap(FrameState& st) const;

  const Scenario& scenario_;
  std::vector<int> first_frame_;                            // per phase
  std::vector<std::unique_ptr<WaypointPath>> paths_;        // per phase (wand and LED)
  std::vector<BodySource> bodies_;                          // per phase (person)
  std::vector<std::shared_ptr<const MocapSource>> mocaps_;  // per phase (mocap)
};

}  // namespace syncap::sim
