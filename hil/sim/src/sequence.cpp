#include "sequence.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace syncap::sim {
namespace {

constexpr int kBlurSamples = 9;

// The wand's middle must stay far enough inside the volume for every target to be inside.
std::unique_ptr<WaypointPath> path_for(const Scenario& sc, const PhaseSpec& ph, int index) {
  double reach = 0, speed = 0;
  if (ph.type == "wand") {
    const auto [lo, hi] =
        std::minmax_element(ph.wand.target_offsets_mm.begin(), ph.wand.target_offsets_mm.end());
    reach = (*hi - *lo) / 2 + ph.wand.target_radius_mm;
    speed = ph.wand.speed_mm_s;
  } else {
    reach = ph.led.radius_mm;
    speed = ph.led.speed_mm_s;
  }
  Eigen::Vector3d lo = sc.volume_min_mm.array() + reach, hi = sc.volume_max_mm.array() - reach;
  hi = hi.cwiseMax(lo + Eigen::Vector3d::Constant(1.0));  // a tiny volume still works
  return std::make_unique<WaypointPath>(lo, hi, speed,
                                        sc.seed * 7919u + static_cast<unsigned>(index));
}

double mean_offset(const std::vector<double>& offsets) {
  return std::accumulate(offsets.begin(), offsets.end(), 0.0) / static_cast<double>(offsets.size());
}

}  // namespace

std::optional<Eigen::Vector3d> marker_centre(const BodyFrame& body, const MarkerSpec& marker,
                                             double radius_mm) {
  for (std::size_t i = 0; i < body.segments.size() && i < body.ellipsoids.size(); ++i) {
    if (body.segments[i] != marker.segment) continue;
    const Ellipsoid& e = body.ellipsoids[i];
    // `at` is a direction on the segment's unit sphere: the surface point is its radii times it.
    const Eigen::Vector3d surface = e.radii_mm.cwiseProduct(marker.at.normalized());
    const Eigen::Vector3d normal =
        surface.cwiseQuotient(e.radii_mm.cwiseProduct(e.radii_mm)).normalized();
    constexpr double kBaseMm = 2;  // the marker's base between skin and sphere
    return Eigen::Vector3d(e.centre_mm + e.axes * (surface + (radius_mm + kBaseMm) * normal));
  }
  return std::nullopt;
}

Sequence::Sequence(const Scenario& scenario, const BodySourceFactory& bodies,
                   const MocapSourceFactory& mocaps)
    : scenario_(scenario) {
  int first = 0;
  for (std::size_t i = 0; i < scenario.phases.size(); ++i) {
    const PhaseSpec& ph = scenario.phases[i];
    first_frame_.push_back(first);
    first += ph.frames;
    const bool moves = ph.type == "wand" || ph.type == "led";
    paths_.push_back(moves ? path_for(scenario, ph, static_cast<int>(i)) : nullptr);
    bodies_.push_back(ph.type == "person" ? bodies(ph.person, scenario) : nullptr);
    mocaps_.push_back(ph.type == "mocap" ? mocaps(ph, scenario) : nullptr);
  }
}

double Sequence::gain_at(int frame) const {
  const double t = frame / scenario_.frame_rate_hz;
  const double span = std::max(1, frames() - 1);
  const ImageSpec& im = scenario_.image;
  return (1.0 + im.drift * frame / span) *
         (1.0 + im.flicker_amplitude * std::sin(2 * M_PI * im.flicker_hz * t));
}

Sphere Sequence::sphere_at(WaypointPath& path, double t, double offset_mm, double radius_mm,
                           double brightness, double exposure_ms) const {
  auto centre = [&](double when) {
    const Pose p = path.at(when);
    return Eigen::Vector3d(p.position + p.attitude * Eigen::Vector3d(offset_mm, 0, 0));
  };
  Sphere s;
  s.centre_mm = centre(t);
  s.radius_mm = radius_mm;
  s.brightness_dn = brightness;
  if (exposure_ms > 0) {
    for (int k = 0; k < kBlurSamples; ++k) {
      const double dt = (static_cast<double>(k) / (kBlurSamples - 1) - 0.5) * exposure_ms * 1e-3;
      s.exposure_path_mm.push_back(centre(t + dt));
    }
  }
  return s;
}

// The markers present at the phase's time as targets (numbered as in the file), the occluders as
// the body, the reflections.
void Sequence::add_mocap(FrameState& st) const {
  const MocapSpec& m = st.phase->mocap;
  const MocapSource& source = *mocaps_[static_cast<std::size_t>(st.phase_index)];
  const MocapFrame frame = source.at(st.phase_time_s);
  st.target_names = &source.names();
  for (std::size_t i = 0; i < frame.markers.size(); ++i) {
    if (!frame.markers[i]) continue;
    Sphere sphere;
    sphere.centre_mm = *frame.markers[i];
    sphere.radius_mm = m.marker_radius_mm;
    sphere.brightness_dn = m.marker_brightness_dn;
    st.content.spheres.push_back(sphere);
    st.target_ids.push_back(static_cast<int>(i));
  }
  st.content.body = frame.occluders;
  st.content.light_dir = m.light_dir.normalized();
  st.content.shadow_darkening = m.shadow_darkening;
  st.content.body_brightness = m.body_brightness;
  st.content.reflections = m.reflections;
  st.content.reflection_seed = scenario_.seed;
}

FrameState Sequence::at(int frame) {
  FrameState st;
  st.frame = frame;
  st.time_s = frame / scenario_.frame_rate_hz;
  const auto it = std::upper_bound(first_frame_.begin(), first_frame_.end(), frame);
  st.phase_index = static_cast<int>(it - first_frame_.begin()) - 1;
  st.phase = &scenario_.phases[static_cast<std::size_t>(st.phase_index)];
  const int in_phase = frame - first_frame_[static_cast<std::size_t>(st.phase_index)];
  st.phase_time_s = in_phase / scenario_.frame_rate_hz;
  const PhaseSpec& ph = *st.phase;
  st.content.room_background = ph.background == "room";
  st.content.gain = gain_at(frame);
  WaypointPath* path = paths_[static_cast<std::size_t>(st.phase_index)].get();
  if (ph.type == "wand") {
    const double mid = mean_offset(ph.wand.target_offsets_mm);
    for (double offset : ph.wand.target_offsets_mm) {
      st.content.spheres.push_back(sphere_at(*path, st.phase_time_s, offset - mid,
                                             ph.wand.target_radius_mm, ph.wand.brightness_dn,
                                             ph.wand.exposure_ms));
    }
  } else if (ph.type == "led") {
    st.led_on = in_phase % (ph.led.on_frames + ph.led.off_frames) < ph.led.on_frames;
    if (st.led_on) {
      st.content.spheres.push_back(
          sphere_at(*path, st.phase_time_s, 0, ph.led.radius_mm, ph.led.brightness_dn, 0));
    }
  } else if (ph.type == "person") {
    st.body = bodies_[static_cast<std::size_t>(st.phase_index)](ph.person.start_s +
                                                                ph.person.speed * st.phase_time_s);
    st.content.body = st.body.ellipsoids;
    st.content.body_mesh = st.body.mesh;
    st.content.light_dir = ph.person.light_dir.normalized();
    st.content.shadow_darkening = ph.person.shadow_darkening;
    st.content.body_brightness = ph.person.body_brightness;
    for (const MarkerSpec& marker : ph.person.markers) {
      Sphere sphere;
      sphere.radius_mm = ph.person.marker_radius_mm;
      sphere.brightness_dn = ph.person.marker_brightness_dn;
      // The scenario's names were checked against the same skeleton.
      sphere.centre_mm = marker_centre(st.body, marker, sphere.radius_mm).value();
      st.content.spheres.push_back(sphere);
    }
  } else if (ph.type == "mocap") {
    add_mocap(st);
  }
  return st;
}

}  // namespace syncap::sim
