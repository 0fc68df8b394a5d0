// A scenario: the cameras, the image formation and the content of a synthetic sequence, phase by
// phase. Loaded from YAML (format in docs/design/scenario.md); every error names file, line and
// problem.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace syncap::sim {

// A scenario that cannot be used; what() is "FILE:LINE: problem".
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CameraPoseSpec {  // explicit layout
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  double omega = 0, phi = 0, kappa = 0;  // rad
};

struct CameraSpec {
  int count = 0;
  std::string layout = "ring";  // ring | half_circle | explicit
  double radius_mm = 3000;      // ring and half circle: distance from the look-at axis
  double height_mm = 2000;      // camera centre height
  double arc_deg = 180;         // half_circle: arc spanned by the cameras
  Eigen::Vector3d look_at_mm{0, 0, 1000};
  std::vector<CameraPoseSpec> poses;  // explicit
  int width_px = 640, height_px = 480;
  double pixel_size_mm = 0.0056;
  double c_mm = 4.0, xp_mm = 0, yp_mm = 0;
  double k1 = 0, k2 = 0, k3 = 0, p1 = 0, p2 = 0, sc = 0, sh = 0;
};

struct ImageSpec {
  double noise_sigma_dn = 1.0;  // Gaussian noise after quantisation-free rendering
  double drift = 0.0;           // relative gain change from first to last frame
  double flicker_hz = 0.0;      // mains flicker of the lamps
  double flicker_amplitude = 0.0;
  double dark_dn = 12.0;  // background of the dark (strobe-lit) phases
};

struct WandSpec {
  std::vector<double> target_offsets_mm{0, 500};  // along the wand from its first end
  double target_radius_mm = 10;
  double brightness_dn = 230;
  double speed_mm_s = 600;
  double exposure_ms = 0;  // > 0: motion blur over this exposure
};

struct LedSpec {
  double radius_mm = 3;
  double brightness_dn = 240;
  double speed_mm_s = 400;
  int on_frames = 1, off_frames = 0;  // switched LED: on for on_frames, then off
};

// A retro-reflective marker on the person: on the surface of an H-Anim segment's ellipsoid
// (host/src/body/hanim_model.cpp) at `at`, a direction on the ellipsoid's unit sphere in the
// segment's own axes (x from the segment's first node to its second, then y and z across; see
// body::Segment): the surface point is radii * at / |at|, so [0.9, 0, 0.44] is near the segment's
// far end on its z side. The marker's centre sits its radius (plus a 2 mm base) outside the
// surface, along the normal.
struct MarkerSpec {
  std::string segment;
  Eigen::Vector3d at = Eigen::Vector3d::UnitY();
  int line = 0;
};

struct PersonSpec {
  // Resolved against the scenario's folder, then $SYNCAP_DATA (default ../shared/data, as the
  // tests'); when found in neither, `bvh_not_found` says where it was looked for.
  std::filesystem::path bvh;
  std::string bvh_not_found;
  double start_s = 0;
  double speed = 1.0;
  // "ellipsoids": the H-Anim body the fit uses; "mesh": the skinned human (skinned_body.hpp),
  // a person who is not the model, of the named subject.
  std::string model = "ellipsoids";
  std::string subject = "average-male";
  Eigen::Vector3d light_dir{0.3, 0.2, -1.0};  // direction the light travels, for the shadow
  double shadow_darkening = 0.45;
  std::vector<MarkerSpec> markers;  // none: a person without markers
  double marker_radius_mm = 7;      // 14 mm markers, as in gait labs
  double marker_brightness_dn = 250;
  // The person's brightness as a share of the lit room's (an infrared mocap camera behind a
  // filter sees the skin and clothes dim beside the markers).
  double body_brightness = 1.0;
};

// A body part of a mocap phase that hides markers: an ellipsoid along the line from the centroid
// of the `from` markers to the centroid of the `to` markers (joint-centre estimates), long
// semi-axis half that length plus radius_mm / 2 (the ends overlap the neighbouring parts), both
// cross semi-axes radius_mm.
struct OccluderSpec {
  std::vector<std::string> from, to;
  double radius_mm = 60;
  int line = 0;
};

// A marker added to a mocap phase: distance_mm from marker `near`'s centre on the line towards
// marker `towards` (a dense marker set built from a sparse one).
struct ExtraMarkerSpec {
  std::string near, towards;
  double distance_mm = 25;
  int line = 0;
};

// Static bright discs in each camera's image (reflections off shiny things), not targets.
struct ReflectionSpec {
  int count = 0;  // per camera
  double radius_px = 2;
  double brightness_dn = 250;
};

// Real marker trajectories (a C3D or TRC file) played back, markers as spheres; the occluders
// stand for the body.
struct MocapSpec {
  std::filesystem::path trajectories;  // resolved as PersonSpec::bvh
  std::string trajectories_not_found;
  std::string up = "z";  // the file's vertical axis: z, or y (OpenSim: X forward, Y up)
  double start_s = 0;
  double speed = 1.0;
  double marker_radius_mm = 7;
  double marker_brightness_dn = 250;
  double body_brightness = 1.0;
  Eigen::Vector3d light_dir{0.3, 0.2, -1.0};
  double shadow_darkening = 0.45;
  std::vector<OccluderSpec> occluders;
  std::vector<ExtraMarkerSpec> extra_markers;
  ReflectionSpec reflections;
};

struct PhaseSpec {
  std::string type;  // wand | led | room | person | mocap
  int frames = 0;
  std::string background = "dark";  // dark | room
  WandSpec wand;
  LedSpec led;
  PersonSpec person;
  MocapSpec mocap;
  int line = 0;  // where in the file, for later errors
};

struct Scenario {
  std::filesystem::path file;
  std::string name;
  unsigned seed = 1;
  double frame_rate_hz = 30;
  Eigen::Vector3d volume_min_mm{-1000, -1000, 0};
  Eigen::Vector3d volume_max_mm{1000, 1000, 2000};
  Eigen::Vector3d room_size_mm{8000, 8000, 3000};  // floor centred on the origin, walls around
  CameraSpec cameras;
  ImageSpec image;
  std::vector<PhaseSpec> phases;
  int total_frames() const;
};

Scenario load_scenario(const std::filesystem::path& file);
// The same from text; `file` is only used in error messages and to resolve relative paths.
Scenario parse_scenario(const std::string& text, const std::filesystem::path& file);

}  // namespace syncap::sim
