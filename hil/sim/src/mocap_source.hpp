// The markers of a mocap phase (docs/design/scenario.md): real marker trajectories from a C3D or
// TRC file turned into the world's axes (Z up), their mean horizontal position moved to the centre
// of the scenario's volume, sampled at any time of the phase; the extra markers placed between
// them and the occluders (the body) drawn along them.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render.hpp"
#include "scenario.hpp"
#include "tracking/marker_trajectories.hpp"

namespace syncap::sim {

// One instant of a mocap phase: every target's centre, the file's markers first in the file's
// order, then the extra markers; nothing where the marker is absent. The occluders whose markers
// are all present.
struct MocapFrame {
  std::vector<std::optional<Eigen::Vector3d>> markers;
  std::vector<Ellipsoid> occluders;
};

// The ellipsoid of an occluder between its two ends: long semi-axis half the length plus
// radius_mm / 2 along the line, both cross semi-axes radius_mm.
Ellipsoid segment_ellipsoid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm);

class MocapSource {
 public:
  // Checks the phase against the trajectories (mm, the file's axes): its length against the
  // clip's, the occluders' and extra markers' names against the file's. Throws ScenarioError
  // "SCENARIO:LINE: problem".
  MocapSource(const tracking::MarkerTrajectories& trajectories, const PhaseSpec& phase,
              const Scenario& scenario);

  MocapFrame at(double phase_time_s) const;
  // The targets' names: the file's markers, then one per extra marker ("A+25mm>B").
  const std::vector<std::string>& names() const { return names_; }
  // From the first sample to the last, s.
  double clip_s() const;
  // One line per marker whose centre lies inside an occluder at that time (hidden from every
  // camera): "SCENARIO:LINE: warning: ...", LINE the occluder's.
  std::vector<std::string> markers_inside_occluders(double phase_time_s) const;

 private:
  struct Occluder {
    std::vector<std::size_t> from, to;
    double radius_mm = 0;
    int line = 0;
  };
  struct Extra {
    std::size_t near = 0, towards = 0;
    double distance_mm = 0;
  };

  void place(const tracking::MarkerTrajectories& trajectories, const Scenario& scenario, int line);
  void check_length(const PhaseSpec& phase, const Scenario& scenario) const;
  std::size_t index_of(const std::string& name, int line) const;
  std::vector<std::size_t> indices_of(const std::vector<std::string>& names, int line) const;
  std::optional<Eigen::Vector3d> file_marker(std::size_t marker, double file_time_s) const;
  std::optional<Eigen::Vector3d> centroid(const std::vector<std::size_t>& markers,
                                          const MocapFrame& frame) const;

  MocapSpec spec_;
  std::string scenario_file_;
  double rate_hz_ = 0;
  std::size_t file_markers_ = 0;
  std::vector<std::vector<std::optional<Eigen::Vector3d>>> world_;  // [sample][marker], placed
  std::vector<std::string> names_;
  std::vector<Occluder> occluders_;
  std::vector<Extra> extras_;
};

// Reads the phase's trajectories (io::read_marker_trajectories; its io::ImportError passes
// through) and prints the warnings of the phase's first frame to stderr.
std::shared_ptr<const MocapSource> open_mocap(const PhaseSpec& phase, const Scenario& scenario);

}  // namespace syncap::sim
