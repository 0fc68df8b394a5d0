#include "mocap_source.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "io/trc_reader.hpp"

namespace syncap::sim {
namespace {

// The file's axes to the world's: Z up as recorded, or OpenSim's Y up with X forward, where
// (X, Y, Z) becomes (X, -Z, Y), a proper rotation.
Eigen::Vector3d to_world(const Eigen::Vector3d& p, const std::string& up) {
  return up == "y" ? Eigen::Vector3d(p.x(), -p.z(), p.y()) : p;
}

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A few of the file's names, for an error about a name it does not have.
std::string some_names(const std::vector<std::string>& names, std::size_t count) {
  std::string list;
  for (std::size_t i = 0; i < names.size() && i < count; ++i) list += (i ? ", " : "") + names[i];
  if (names.size() > count) list += ", ... (" + std::to_string(names.size()) + " in all)";
  return list;
}

bool inside(const Ellipsoid& e, const Eigen::Vector3d& p) {
  const Eigen::Vector3d local = e.axes.transpose() * (p - e.centre_mm);
  return local.cwiseQuotient(e.radii_mm).squaredNorm() < 1.0;
}

}  // namespace

Ellipsoid segment_ellipsoid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm) {
  const double length = (b - a).norm();
  const Eigen::Vector3d x =
      length > 1e-9 ? Eigen::Vector3d((b - a) / length) : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d helper =
      std::abs(x.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y = x.cross(helper).normalized();
  Ellipsoid e;
  e.centre_mm = (a + b) / 2;
  e.axes.col(0) = x;
  e.axes.col(1) = y;
  e.axes.col(2) = x.cross(y);
  e.radii_mm = {length / 2 + radius_mm / 2, radius_mm, radius_mm};
  return e;
}

MocapSource::MocapSource(const tracking::MarkerTrajectories& trajectories, const PhaseSpec& phase,
                         const Scenario& scenario)
    : spec_(phase.mocap),
      scenario_file_(scenario.file.string()),
      rate_hz_(trajectories.rate_hz),
      file_markers_(trajectories.labels.size()),
      names_(trajectories.labels) {
  if (!(rate_hz_ > 0) || trajectories.samples.empty()) {
    throw ScenarioError(scenario_file_ + ":" + std::to_string(phase.line) + ": " +
                        spec_.trajectories.string() + " has no samples or no frame rate");
  }
  place(trajectories, scenario, phase.line);
  check_length(phase, scenario);
  for (const OccluderSpec& o : spec_.occluders) {
    occluders_.push_back(
        {indices_of(o.from, o.line), indices_of(o.to, o.line), o.radius_mm, o.line});
  }
  for (const ExtraMarkerSpec& e : spec_.extra_markers) {
    extras_.push_back({index_of(e.near, e.line), index_of(e.towards, e.line), e.distance_mm});
    names_.push_back(e.near + "+" + fmt(e.distance_mm) + "mm>" + e.towards);
  }
}

// Samples to world axes; the mean horizontal position of every present marker in every sample
// moved to the volume's centre, heights kept (labs put the floor at 0).
void MocapSource::place(const tracking::MarkerTrajectories& trajectories, const Scenario& scenario,
                        int line) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double count = 0;
  for (const auto& row : trajectories.samples) {
    auto& out = world_.emplace_back(file_markers_);
    for (std::size_t m = 0; m < row.size() && m < file_markers_; ++m) {
      if (!row[m]) continue;
      out[m] = to_world(row[m]->position_mm, spec_.up);
      sum += out[m]->head<2>();
      ++count;
    }
  }
  if (count == 0) {
    throw ScenarioError(scenario_file_ + ":" + std::to_string(line) + ": " +
                        spec_.trajectories.string() + " has no marker in any frame");
  }
  const Eigen::Vector2d centre = (scenario.volume_min_mm + scenario.volume_max_mm).head<2>() / 2;
  const Eigen::Vector3d shift((centre - sum / count).x(), (centre - sum / count).y(), 0);
  for (auto& row : world_) {
    for (auto& p : row) {
      if (p) *p += shift;
    }
  }
}

// The phase must end inside the clip: a loop would be a jump real people do not make.
void MocapSource::check_length(const PhaseSpec& phase, const Scenario& scenario) const {
  const double last_s = (phase.frames - 1) / scenario.frame_rate_hz;
  const double end_s = spec_.start_s + spec_.speed * last_s;
  if (end_s <= clip_s() + 1e-9) return;
  const double fits = (clip_s() - spec_.start_s) / spec_.speed * scenario.frame_rate_hz;
  const std::string most =
      fits < 0 ? "start_s is past its end"
               : "at most " + std::to_string(static_cast<long>(std::floor(fits + 1e-9)) + 1) +
                     " frames at " + fmt(scenario.frame_rate_hz) + " Hz";
  throw ScenarioError(scenario_file_ + ":" + std::to_string(phase.line) +
                      ": the mocap phase plays " + spec_.trajectories.string() + " from " +
                      fmt(spec_.start_s) + " s to " + fmt(end_s) + " s but the clip is " +
                      fmt(clip_s()) + " s long (" + std::to_string(world_.size()) + " samples at " +
                      fmt(rate_hz_) + " Hz): " + most + " (a mocap phase does not loop)");
}

double MocapSource::clip_s() const { return static_cast<double>(world_.size() - 1) / rate_hz_; }

std::size_t MocapSource::index_of(const std::string& name, int line) const {
  for (std::size_t m = 0; m < file_markers_; ++m) {
    if (names_[m] == name) return m;
  }
  throw ScenarioError(scenario_file_ + ":" + std::to_string(line) + ": no marker '" + name +
                      "' in " + spec_.trajectories.string() + " (it has " + some_names(names_, 8) +
                      ")");
}

std::vector<std::size_t> MocapSource::indices_of(const std::vector<std::string>& names,
                                                 int line) const {
  std::vector<std::size_t> out;
  for (const std::string& name : names) out.push_back(index_of(name, line));
  return out;
}

// Linear interpolation between the two samples around the time; absent when either is a gap.
// A time on a sample (within 1e-6 of its interval) takes that sample alone.
std::optional<Eigen::Vector3d> MocapSource::file_marker(std::size_t marker,
                                                        double file_time_s) const {
  if (world_.size() == 1) return world_[0][marker];
  const double s = file_time_s * rate_hz_;
  const double last = static_cast<double>(world_.size() - 1);
  const double nearest = std::round(s);
  if (std::abs(s - nearest) < 1e-6) {
    return world_[static_cast<std::size_t>(std::clamp(nearest, 0.0, last))][marker];
  }
  const double below = std::clamp(std::floor(s), 0.0, last - 1);
  const auto& a = world_[static_cast<std::size_t>(below)][marker];
  const auto& b = world_[static_cast<std::size_t>(below) + 1][marker];
  if (!a || !b) return std::nullopt;
  const double f = std::clamp(s - below, 0.0, 1.0);
  return Eigen::Vector3d(*a + f * (*b - *a));
}

std::optional<Eigen::Vector3d> MocapSource::centroid(const std::vector<std::size_t>& markers,
                                                     const MocapFrame& frame) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t m : markers) {
    if (!frame.markers[m]) return std::nullopt;
    sum += *frame.markers[m];
  }
  return Eigen::Vector3d(sum / static_cast<double>(markers.size()));
}

MocapFrame MocapSource::at(double phase_time_s) const {
  MocapFrame frame;
  const double file_time_s = spec_.start_s + spec_.speed * phase_time_s;
  for (std::size_t m = 0; m < file_markers_; ++m)
    frame.markers.push_back(file_marker(m, file_time_s));
  for (const Extra& e : extras_) {
    const auto& a = frame.markers[e.near];
    const auto& b = frame.markers[e.towards];
    if (!a || !b || (*b - *a).norm() < 1e-9) {
      frame.markers.emplace_back();
      continue;
    }
    frame.markers.emplace_back(*a + e.distance_mm * (*b - *a).normalized());
  }
  for (const Occluder& o : occluders_) {
    const auto a = centroid(o.from, frame), b = centroid(o.to, frame);
    if (a && b) frame.occluders.push_back(segment_ellipsoid(*a, *b, o.radius_mm));
  }
  return frame;
}

std::vector<std::string> MocapSource::markers_inside_occluders(double phase_time_s) const {
  const MocapFrame frame = at(phase_time_s);
  std::vector<std::string> warnings;
  for (const Occluder& o : occluders_) {
    const auto a = centroid(o.from, frame), b = centroid(o.to, frame);
    if (!a || !b) continue;
    const Ellipsoid e = segment_ellipsoid(*a, *b, o.radius_mm);
    for (std::size_t m = 0; m < frame.markers.size(); ++m) {
      if (!frame.markers[m] || !inside(e, *frame.markers[m])) continue;
      warnings.push_back(scenario_file_ + ":" + std::to_string(o.line) + ": warning: marker " +
                         names_[m] + "'s centre is inside this occluder at " + fmt(phase_time_s) +
                         " s of the phase (hidden from every camera)");
    }
  }
  return warnings;
}

std::shared_ptr<const MocapSource> open_mocap(const PhaseSpec& phase, const Scenario& scenario) {
  if (!phase.mocap.trajectories_not_found.empty()) {
    throw ScenarioError(scenario.file.string() + ":" + std::to_string(phase.line) +
                        ": trajectories " + phase.mocap.trajectories_not_found);
  }
  auto source = std::make_shared<const MocapSource>(
      io::read_marker_trajectories(phase.mocap.trajectories.string()), phase, scenario);
  for (const std::string& warning : source->markers_inside_occluders(0)) {
    std::cerr << "syncap-sim: " << warning << "\n";
  }
  return source;
}

}  // namespace syncap::sim
