// The fit on a real captured motion (../shared/data/motion/mixamo-free.bvh, 69 frames of a walk
// at 30 Hz, retargeted onto the thesis body as the replay scenes are): the body's surface sampled
// with 3 mm of noise and fitted. The motion turns every joint (the vertebrae, the fingers, the
// feet's small joints), the fit has 18: its error is measured against the real pose, beside the
// ceiling (the parameters nearest the real pose).
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <random>

#include "body/bvh.hpp"
#include "body/hanim_model.hpp"
#include "body/retarget.hpp"
#include "body_scenes.hpp"
#include "fitting/surface_fit.hpp"
#include "syncap_test_data.hpp"

namespace syncap::fitting {
namespace {

// RMS over the segments' end points between a fitted pose and the real one [mm].
double ends_rms_mm(const PoseParameters& parameters, const PoseVector& x,
                   const body::BodyFrame& truth) {
  const body::Skeleton& skeleton = parameters.skeleton();
  const auto fitted = body::node_positions(skeleton, parameters.pose(x.data()));
  std::vector<bool> end(skeleton.size(), false);
  for (const body::Segment& s : skeleton.segments())
    end[static_cast<std::size_t>(s.from)] = end[static_cast<std::size_t>(s.to)] = true;
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    if (!end[i]) continue;
    sum += (fitted[i] - truth.positions_mm[i]).squaredNorm();
    ++n;
  }
  return std::sqrt(sum / n);
}

struct WalkFits {
  int fits = 0;
  double mean_mm = 0.0, worst_mm = 0.0, worst_ceiling_mm = 0.0;
  double mean_points_used = 0.0;  // share of the points within the fit's last gate
};

// Fits every `step`-th frame of the walk. `track`: each frame from the last one's result (the
// first from the parameters nearest the real pose, moved by 0.05 rad per joint axis and 30 mm);
// otherwise each frame from its own nearest parameters, moved the same way.
WalkFits fit_walk(const std::filesystem::path& bvh, int step, bool track) {
  body::RetargetOptions options;
  options.volume = body::CaptureVolume{};
  const body::BvhRetargeter motion(body::hanim_skeleton(), body::load_bvh(bvh), options);
  const PoseParameters parameters(motion.skeleton());
  std::mt19937 rng(5);
  WalkFits w;
  PoseVector x{};
  for (int frame = 0; frame < motion.bvh().frame_count; frame += step) {
    const body::Pose real = motion.pose_at_frame(frame);
    const body::BodyFrame truth = body::body_frame(motion.skeleton(), real);
    const PoseVector ceiling = parameters.nearest(real);
    if (frame == 0 || !track) {
      x = ceiling;
      for (std::size_t i = 6; i < x.size(); ++i) x[i] += 0.05;
      x[0] += 30.0;
    }
    const std::vector<SurfacePoint> points = test::surface_points(truth, 40, rng, 3.0, 3.0);
    const SurfaceFit fit = fit_surface(parameters, points, x);
    x = fit.x;
    const double rms = ends_rms_mm(parameters, fit.x, truth);
    w.worst_mm = std::max(w.worst_mm, rms);
    w.worst_ceiling_mm = std::max(w.worst_ceiling_mm, ends_rms_mm(parameters, ceiling, truth));
    w.mean_mm += rms;
    w.mean_points_used += static_cast<double>(fit.points) / static_cast<double>(points.size());
    ++w.fits;
  }
  w.mean_mm /= w.fits;
  w.mean_points_used /= w.fits;
  return w;
}

std::ostream& operator<<(std::ostream& out, const WalkFits& w) {
  return out << w.fits << " frames, segment ends RMS mean " << w.mean_mm << " mm, worst "
             << w.worst_mm << " mm, points within the last gate " << 100 * w.mean_points_used
             << " %; the parameters' ceiling (nearest the real pose) worst " << w.worst_ceiling_mm
             << " mm";
}

// Each frame on its own from a start near it: the fit lands on the real pose within what the 18
// joints can say of it. Measured 2026-11-27 (12 frames): see docs/body-fit.md.
TEST(MixamoFit, FitsEveryFrameOfTheRealWalkFromANearbyStart) {
  SYNCAP_REQUIRE_DATA(path, "motion/mixamo-free.bvh");
  const WalkFits w = fit_walk(path, 6, false);
  std::cout << "mixamo fit, per frame: " << w << "\n";
  EXPECT_LT(w.worst_ceiling_mm, 35.0);  // measured 33.1 mm
  EXPECT_LT(w.mean_mm, 20.0);           // 13.0 mm
  EXPECT_LT(w.worst_mm, 25.0);          // 16.9 mm
}

// Frame to frame through the walk (every third frame: 0.1 s apart), as a tracker would run the
// fit: the figure of what tracking still lacks (docs/body-fit.md). Disabled: a minute, and the
// track is lost today. Run: host_fitting_mixamo_data_test --gtest_also_run_disabled_tests.
TEST(MixamoFit, DISABLED_TracksTheRealWalkFrameToFrame) {
  SYNCAP_REQUIRE_DATA(path, "motion/mixamo-free.bvh");
  const WalkFits w = fit_walk(path, 3, true);
  std::cout << "mixamo fit, tracked: " << w << "\n";
  EXPECT_LT(w.mean_mm, 40.0);
}

}  // namespace
}  // namespace syncap::fitting
