// The mocap phase (docs/design/scenario.md): real marker trajectories from a TRC or C3D file,
// here tiny TRC files written to a temporary folder: parsing and its errors, the file's axes to
// the world's, placement in the volume, interpolation and gaps, occluders, extra markers,
// reflections.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "camera_rig.hpp"
#include "io/import_error.hpp"
#include "mocap_source.hpp"
#include "reflections.hpp"
#include "render.hpp"
#include "scenario.hpp"
#include "sequence.hpp"

namespace syncap::sim {
namespace {

namespace fs = std::filesystem;

// A TRC file of `names` at `rate_hz`; rows[f][m] is "x\ty\tz" or "" (a gap).
struct Trc {
  std::vector<std::string> names;
  double rate_hz = 10;
  std::vector<std::vector<std::string>> rows;
};

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("syncap_mocap_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

void write_trc(const fs::path& path, const Trc& trc) {
  std::ofstream out(path);
  out << "PathFileType\t4\t(X/Y/Z)\t" << path.filename().string() << "\n"
      << "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n"
      << trc.rate_hz << "\t" << trc.rate_hz << "\t" << trc.rows.size() << "\t" << trc.names.size()
      << "\tmm\n"
      << "Frame#\tTime";
  for (const auto& name : trc.names) out << "\t" << name << "\t\t";
  out << "\n\t";
  for (std::size_t m = 1; m <= trc.names.size(); ++m) out << "\tX" << m << "\tY" << m << "\tZ" << m;
  out << "\n\n";
  for (std::size_t f = 0; f < trc.rows.size(); ++f) {
    out << f + 1 << "\t" << f / trc.rate_hz;
    for (const auto& p : trc.rows[f]) out << "\t" << (p.empty() ? "\t\t" : p);
    out << "\n";
  }
}

// Y up (OpenSim), 10 Hz, 3 samples: A moves along X, B too, C has a gap in the middle sample.
// In the world (X, -Z, Y): A (0..20, 0, 1000), B (100..120, 50, 1200), C (50, -100, 1100).
const Trc kYUp{{"A", "B", "C"},
               10,
               {{"0\t1000\t0", "100\t1200\t-50", "50\t1100\t100"},
                {"10\t1000\t0", "110\t1200\t-50", ""},
                {"20\t1000\t0", "120\t1200\t-50", "50\t1100\t100"}}};

// The mean horizontal position of kYUp's present markers: x (30 + 330 + 100) / 8, y (150 - 200)
// / 8; the scenario below centres the volume on (1000, 500).
const Eigen::Vector3d kShift(1000 - 460.0 / 8, 500 + 50.0 / 8, 0);

std::string mocap_scenario(const std::string& file, const std::string& phase_extra,
                           int frames = 5) {
  return "frame_rate_hz: 20\nvolume_min_mm: [0, 0, 0]\nvolume_max_mm: [2000, 1000, 2000]\n"
         "cameras: {count: 2, radius_mm: 3000, height_mm: 1000, look_at_mm: [1000, 500, 1000],\n"
         "          width_px: 320, height_px: 240, pixel_size_mm: 0.01, c_mm: 4}\n"
         "image: {noise_sigma_dn: 0}\n"
         "phases:\n"
         "  - type: mocap\n"
         "    frames: " +
         std::to_string(frames) + "\n    trajectories: " + file + "\n" + phase_extra;
}

Scenario scenario_with(const Trc& trc, const std::string& phase_extra, int frames = 5) {
  const fs::path dir = temp_dir();
  write_trc(dir / "tiny.trc", trc);
  const fs::path file = dir / "tiny.yaml";
  std::ofstream(file) << mocap_scenario("tiny.trc", phase_extra, frames);
  return load_scenario(file);
}

std::string error_of(const Scenario& sc) {
  try {
    open_mocap(sc.phases.at(0), sc);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MocapPhase, IsReadWithItsKeysAndDefaults) {
  const Scenario sc = scenario_with(kYUp,
                                    "    up: y\n    speed: 0.5\n    marker_radius_mm: 9.5\n"
                                    "    occluders:\n"
                                    "      - {from: [A], to: [B, C], radius_mm: 40}\n"
                                    "    extra_markers:\n"
                                    "      - {near: A, towards: B, distance_mm: 20}\n"
                                    "    reflections: {count: 3, radius_px: 1.5}\n");
  const MocapSpec& m = sc.phases.at(0).mocap;
  EXPECT_EQ(sc.phases[0].type, "mocap");
  EXPECT_EQ(sc.phases[0].background, "dark");
  EXPECT_EQ(m.trajectories.string(), (temp_dir() / "tiny.trc").string());
  EXPECT_EQ(m.up, "y");
  EXPECT_DOUBLE_EQ(m.start_s, 0);
  EXPECT_DOUBLE_EQ(m.speed, 0.5);
  EXPECT_DOUBLE_EQ(m.marker_radius_mm, 9.5);
  EXPECT_DOUBLE_EQ(m.marker_brightness_dn, 250);
  ASSERT_EQ(m.occluders.size(), 1u);
  EXPECT_EQ(m.occluders[0].to, (std::vector<std::string>{"B", "C"}));
  EXPECT_EQ(m.occluders[0].line, 15);
  ASSERT_EQ(m.extra_markers.size(), 1u);
  EXPECT_EQ(m.extra_markers[0].towards, "B");
  EXPECT_EQ(m.reflections.count, 3);
  EXPECT_DOUBLE_EQ(m.reflections.brightness_dn, 250);
}

TEST(MocapPhase, ParsingErrorsNameTheLine) {
  const auto parse_error = [](const std::string& extra) {
    try {
      parse_scenario(mocap_scenario("x.trc", extra), "broken.yaml");
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(parse_error("    up: x\n"), "broken.yaml:11: phases[0].up 'x' is not one of: y, z");
  EXPECT_EQ(parse_error("    occluders: [{from: A, to: [B], radius_mm: 4}]\n"),
            "broken.yaml:11: mocap.occluders[].from must be a list of names [A, B, ...]");
  EXPECT_EQ(parse_error("    extra_markers: [{near: A, towards: B}]\n"),
            "broken.yaml:11: mocap.extra_markers[] needs 'distance_mm'");
  EXPECT_EQ(parse_error("    reflection: {count: 2}\n"),
            "broken.yaml:11: unknown key 'reflection' in phases[0]");
}

TEST(MocapPhase, UnknownMarkerNamesItsLineAndSomeKnownNames) {
  const Scenario sc = scenario_with(
      kYUp, "    up: y\n    occluders:\n      - {from: [A], to: [Z], radius_mm: 40}\n");
  const std::string e = error_of(sc);
  EXPECT_NE(e.find("tiny.yaml:13: no marker 'Z' in "), std::string::npos) << e;
  EXPECT_NE(e.find("(it has A, B, C)"), std::string::npos) << e;
  const Scenario extra =
      scenario_with(kYUp, "    extra_markers:\n      - {near: Q, towards: A, distance_mm: 10}\n");
  EXPECT_NE(error_of(extra).find("tiny.yaml:12: no marker 'Q'"), std::string::npos)
      << error_of(extra);
}

TEST(MocapPhase, APhaseLongerThanTheClipNamesItsLineAndTheClipsLength) {
  EXPECT_EQ(error_of(scenario_with(kYUp, "", 5)), "no error");  // 0.2 s at 20 Hz: 5 frames
  const std::string e = error_of(scenario_with(kYUp, "", 6));
  EXPECT_NE(e.find("tiny.yaml:8: the mocap phase plays "), std::string::npos) << e;
  EXPECT_NE(e.find("to 0.25 s but the clip is 0.2 s long (3 samples at 10 Hz): at most 5 frames"),
            std::string::npos)
      << e;
  const std::string slow = error_of(scenario_with(kYUp, "    start_s: 0.1\n    speed: 0.5\n", 6));
  EXPECT_NE(slow.find("at most 5 frames"), std::string::npos) << slow;
}

TEST(MocapPhase, AMissingFileNamesBothPlacesAndABrokenOneIsAnImportError) {
  const fs::path dir = temp_dir();
  std::ofstream(dir / "lost.yaml") << mocap_scenario("motion/none.trc", "");
  const Scenario sc = load_scenario(dir / "lost.yaml");
  const std::string e = error_of(sc);
  EXPECT_NE(e.find("lost.yaml:8: trajectories motion/none.trc is neither beside the scenario"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("$SYNCAP_DATA"), std::string::npos) << e;
  std::ofstream(dir / "broken.trc") << "not a trc\n";
  std::ofstream(dir / "broken.yaml") << mocap_scenario("broken.trc", "");
  const Scenario broken = load_scenario(dir / "broken.yaml");
  EXPECT_THROW(open_mocap(broken.phases[0], broken), io::ImportError);
}

TEST(MocapPhase, YUpFileIsTurnedAndCentredInTheVolumeHeightsKept) {
  const Scenario sc = scenario_with(kYUp, "    up: y\n");
  const auto source = open_mocap(sc.phases[0], sc);
  EXPECT_EQ(source->names(), (std::vector<std::string>{"A", "B", "C"}));
  EXPECT_DOUBLE_EQ(source->clip_s(), 0.2);
  const MocapFrame f = source->at(0);
  ASSERT_EQ(f.markers.size(), 3u);
  ASSERT_TRUE(f.markers[0] && f.markers[1] && f.markers[2]);
  EXPECT_LT((*f.markers[0] - (Eigen::Vector3d(0, 0, 1000) + kShift)).norm(), 1e-9);
  EXPECT_LT((*f.markers[1] - (Eigen::Vector3d(100, 50, 1200) + kShift)).norm(), 1e-9);
  EXPECT_LT((*f.markers[2] - (Eigen::Vector3d(50, -100, 1100) + kShift)).norm(), 1e-9);
}

TEST(MocapPhase, ZUpFileKeepsItsAxes) {
  const Scenario sc = scenario_with(kYUp, "");
  const MocapFrame f = open_mocap(sc.phases[0], sc)->at(0);
  // File (100, 1200, -50) as it is, shifted by the mean of the file's x and y.
  const Eigen::Vector3d shift(1000 - 460.0 / 8, 500 - (3000 + 3600 + 2200) / 8.0, 0);
  EXPECT_LT((*f.markers[1] - (Eigen::Vector3d(100, 1200, -50) + shift)).norm(), 1e-9);
}

TEST(MocapPhase, SamplesBetweenFramesAreInterpolatedAndAGapMakesTheMarkerAbsent) {
  const Scenario sc = scenario_with(kYUp, "    up: y\n");
  const auto source = open_mocap(sc.phases[0], sc);
  const MocapFrame half = source->at(0.05);  // halfway between samples 0 and 1
  ASSERT_TRUE(half.markers[0]);
  EXPECT_LT((*half.markers[0] - (Eigen::Vector3d(5, 0, 1000) + kShift)).norm(), 1e-9);
  EXPECT_FALSE(half.markers[2]);              // sample 1 is a gap
  EXPECT_FALSE(source->at(0.1).markers[2]);   // on the gap
  EXPECT_FALSE(source->at(0.15).markers[2]);  // after it
  EXPECT_TRUE(source->at(0.2).markers[2]);    // on the last sample
  const MocapFrame later = source->at(0.15);
  EXPECT_LT((*later.markers[1] - (Eigen::Vector3d(115, 50, 1200) + kShift)).norm(), 1e-9);
  // start_s and speed: file time = start_s + speed * phase time.
  const Scenario slow = scenario_with(kYUp, "    up: y\n    start_s: 0.1\n    speed: 0.5\n");
  const MocapFrame s = open_mocap(slow.phases[0], slow)->at(0.1);  // file time 0.15
  EXPECT_LT((*s.markers[0] - (Eigen::Vector3d(15, 0, 1000) + kShift)).norm(), 1e-9);
}

TEST(MocapPhase, AbsentMarkersAreNoTargetsAndTheOthersKeepTheirNumbers) {
  const Scenario sc = scenario_with(kYUp, "    up: y\n");
  Sequence sequence(sc, [](const PersonSpec&, const Scenario&) { return BodySource(); });
  const FrameState gap = sequence.at(2);  // phase time 0.1 s: C's gap
  ASSERT_EQ(gap.content.spheres.size(), 2u);
  EXPECT_EQ(gap.target_ids, (std::vector<int>{0, 1}));
  const FrameState all = sequence.at(4);
  EXPECT_EQ(all.target_ids, (std::vector<int>{0, 1, 2}));
  ASSERT_NE(all.target_names, nullptr);
  EXPECT_EQ(all.target_names->at(2), "C");
  EXPECT_DOUBLE_EQ(all.content.spheres[0].radius_mm, 7);
}

// A column (the occluder from O1 up to O2) stands between camera 0 (on the -Y side) and marker
// M beside it: camera 0 does not see M, camera 1 (opposite) does.
const Trc kColumn{
    {"O1", "O2", "M"},
    10,
    {{"0\t0\t800", "0\t0\t1200", "0\t150\t1000"}, {"0\t0\t800", "0\t0\t1200", "0\t150\t1000"}}};

TEST(MocapPhase, AnOccluderHidesAMarkerBehindItFromOneCameraNotTheOpposite) {
  const Scenario sc = scenario_with(kColumn,
                                    "    body_brightness: 0.2\n    occluders:\n"
                                    "      - {from: [O1], to: [O2], radius_mm: 80}\n",
                                    2);
  const auto source = open_mocap(sc.phases[0], sc);
  // The column's ends are its single markers: inside it (a warning each); M is not.
  const auto warnings = source->markers_inside_occluders(0);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[1].find("marker O2's"), std::string::npos) << warnings[1];
  Sequence sequence(sc, [](const PersonSpec&, const Scenario&) { return BodySource(); });
  const FrameState st = sequence.at(0);
  ASSERT_EQ(st.content.body.size(), 1u);
  EXPECT_NEAR(st.content.body[0].radii_mm.x(), 200 + 40, 1e-9);  // half the length plus R / 2
  EXPECT_NEAR(st.content.body[0].radii_mm.y(), 80, 1e-9);
  const auto rig = build_rig(sc);
  const RenderedView front = render_view(make_view(rig[0], sc), st.content, sc.image, 1);
  const RenderedView back = render_view(make_view(rig[1], sc), st.content, sc.image, 1);
  ASSERT_EQ(front.spheres.size(), 3u);
  EXPECT_FALSE(front.spheres[2].visible);
  EXPECT_TRUE(back.spheres[2].visible);
  EXPECT_GT(cv::countNonZero(front.mask), 100);  // the occluder is drawn as the body
}

TEST(MocapPhase, AMarkerInsideAnOccluderIsWarnedAbout) {
  const Scenario sc = scenario_with(kColumn,
                                    "    occluders:\n"
                                    "      - {from: [O1], to: [O2], radius_mm: 200}\n",
                                    2);
  const auto warnings = open_mocap(sc.phases[0], sc)->markers_inside_occluders(0);
  ASSERT_EQ(warnings.size(), 3u);  // O1 and O2 on the axis, M 150 mm from it
  EXPECT_NE(warnings[2].find("tiny.yaml:12: warning: marker M's centre is inside this occluder"),
            std::string::npos)
      << warnings[2];
}

TEST(MocapPhase, AnExtraMarkerLiesAtItsDistanceTowardsTheOther) {
  const Scenario sc = scenario_with(kColumn,
                                    "    extra_markers:\n"
                                    "      - {near: O1, towards: O2, distance_mm: 25}\n"
                                    "      - {near: M, towards: O1, distance_mm: 30}\n",
                                    2);
  const auto source = open_mocap(sc.phases[0], sc);
  ASSERT_EQ(source->names().size(), 5u);
  EXPECT_EQ(source->names()[3], "O1+25mm>O2");
  const MocapFrame f = source->at(0.05);
  ASSERT_EQ(f.markers.size(), 5u);
  EXPECT_LT((*f.markers[3] - (*f.markers[0] + Eigen::Vector3d(0, 0, 25))).norm(), 1e-9);
  EXPECT_NEAR((*f.markers[4] - *f.markers[2]).norm(), 30, 1e-9);
  const Eigen::Vector3d towards = (*f.markers[0] - *f.markers[2]).normalized();
  EXPECT_NEAR((*f.markers[4] - *f.markers[2]).normalized().dot(towards), 1, 1e-12);
}

TEST(MocapPhase, AnExtraMarkerIsAbsentWhenEitherOfItsMarkersIs) {
  const Scenario sc = scenario_with(kYUp,
                                    "    up: y\n    extra_markers:\n"
                                    "      - {near: A, towards: C, distance_mm: 10}\n");
  const auto source = open_mocap(sc.phases[0], sc);
  EXPECT_TRUE(source->at(0).markers[3]);
  EXPECT_FALSE(source->at(0.1).markers[3]);
}

TEST(MocapPhase, ReflectionsAreReproducibleStaticDiscsAndNoTargets) {
  ReflectionSpec spec;
  spec.count = 6;
  spec.radius_px = 2;
  const auto a = reflection_discs(spec, 7, 0, 320, 240);
  const auto b = reflection_discs(spec, 7, 0, 320, 240);
  const auto other = reflection_discs(spec, 7, 1, 320, 240);
  ASSERT_EQ(a.size(), 6u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].centre_px, b[i].centre_px);
    EXPECT_NE(a[i].centre_px, other[i].centre_px);
    EXPECT_GE(a[i].centre_px.x(), 3);
    EXPECT_LE(a[i].centre_px.y(), 240 - 4);
  }
  const Scenario sc =
      scenario_with(kColumn, "    reflections: {count: 6, radius_px: 2, brightness_dn: 240}\n", 2);
  Sequence sequence(sc, [](const PersonSpec&, const Scenario&) { return BodySource(); });
  const auto rig = build_rig(sc);
  const View view = make_view(rig[1], sc);
  const RenderedView first = render_view(view, sequence.at(0).content, sc.image, 1);
  const RenderedView second = render_view(view, sequence.at(1).content, sc.image, 2);
  EXPECT_EQ(first.spheres.size(), 3u);  // the markers only
  for (const ImageDisc& d :
       reflection_discs(sc.phases[0].mocap.reflections, sc.seed, 1, 320, 240)) {
    const int x = static_cast<int>(std::lround(d.centre_px.x()));
    const int y = static_cast<int>(std::lround(d.centre_px.y()));
    EXPECT_GE(first.image.at<uint8_t>(y, x), 200) << x << "," << y;
    EXPECT_EQ(first.image.at<uint8_t>(y, x), second.image.at<uint8_t>(y, x));
  }
}

}  // namespace
}  // namespace syncap::sim
