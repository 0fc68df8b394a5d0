#include "reconstruction/marker_stage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "outputs/marker_message_stage.hpp"
#include "reconstruction/tracking_stage.hpp"
#include "synthetic_markers.hpp"

namespace syncap::reconstruction {
namespace {

// The synthetic frame as the grouper hands it out: one blob frame per camera id.
pipeline::FrameWork work_of(const test::MarkerFrame& f,
                            const std::vector<sensor::CameraModel>& cameras) {
  pipeline::FrameWork w;
  w.group.frame_number = 42;
  w.group.trigger = trigger_t{};
  w.group.trigger->frame_number = 42;
  w.ready = std::chrono::steady_clock::now();
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    blob_frame_t b{};
    b.camera_id = static_cast<int16_t>(cameras[c].id);
    b.frame_number = 42;
    for (const Eigen::Vector2d& p : f.blobs[c]) {
      blob_t blob{};
      blob.x = static_cast<float>(p.x());
      blob.y = static_cast<float>(p.y());
      b.blobs.push_back(blob);
    }
    b.num_blobs = static_cast<int16_t>(b.blobs.size());
    w.group.blobs[cameras[c].id] = b;
  }
  return w;
}

// One marker at a random place, seen by every camera without noise.
std::pair<std::vector<Eigen::Vector3d>, test::MarkerFrame> one_exact_marker(
    const std::vector<sensor::CameraModel>& cameras, unsigned seed) {
  std::mt19937 rng(seed);
  test::MarkerFrameOptions o;
  o.hidden = 0;
  o.spurious_per_camera = 0;
  o.noise_px = 0.0;
  auto truth = test::random_markers(rng, 1);
  test::MarkerFrame f = test::observe(cameras, truth, o, rng);
  return {std::move(truth), std::move(f)};
}

TEST(MarkerStage, TheMarkersOfAGroupAreFoundWithTheirCameraIds) {
  auto cameras = test::marker_ring(6);
  for (auto& c : cameras) c.id += 10;  // ids are not indices
  std::mt19937 rng(3);
  test::MarkerFrameOptions o;
  o.hidden = 0;
  o.spurious_per_camera = 0;
  o.noise_px = 0.05;  // float pixels in blob_t: ~1e-4 px more
  const auto truth = test::random_markers(rng, 20);
  const test::MarkerFrame f = test::observe(cameras, truth, o, rng);
  pipeline::FrameWork w = work_of(f, cameras);
  blob_frame_t stranger{};  // a camera the calibration does not know
  stranger.camera_id = 3;
  stranger.blobs.resize(4);
  w.group.blobs[3] = stranger;

  MarkerStage stage(cameras, {});
  stage.process(w);
  ASSERT_EQ(w.markers.size(), 20u);
  for (const pipeline::Marker3d& m : w.markers) {
    double nearest = 1e9;
    for (const Eigen::Vector3d& t : truth) nearest = std::min(nearest, (m.position - t).norm());
    EXPECT_LT(nearest, 1.0);
    EXPECT_EQ(m.camera_ids.size(), 6u);
    EXPECT_EQ(m.camera_ids.front(), 10);
    EXPECT_GT(m.covariance(0, 0), 0);
  }
  EXPECT_EQ(stage.stats().blobs_of_unknown_cameras, 4);
  EXPECT_EQ(stage.stats().blobs_used, 120);
}

// A blob the edge flagged NOT_ROUND (a partly hidden or merged spot, here 0.3 px off) is left out
// and counted; with keep_not_round it takes part and pulls its marker away.
TEST(MarkerStage, BlobsFlaggedNotRoundAreLeftOutUnlessKept) {
  const auto cameras = test::marker_ring(6);
  const auto [truth, f] = one_exact_marker(cameras, 5);
  struct Outcome {
    double error_mm = 1e9;
    MarkerStageStats stats;
  };
  auto run = [&](bool keep) {
    pipeline::FrameWork w = work_of(f, cameras);
    blob_t& cut = w.group.blobs[cameras[0].id].blobs.at(0);
    cut.x += 0.3f;
    cut.flags = blob_t::FLAG_NOT_ROUND;
    MarkerStageOptions options;
    options.keep_not_round = keep;
    MarkerStage stage(cameras, {}, options);
    stage.process(w);
    Outcome out;
    out.stats = stage.stats();
    if (w.markers.size() == 1) out.error_mm = (w.markers[0].position - truth[0]).norm();
    return out;
  };
  const Outcome left_out = run(false), kept = run(true);
  EXPECT_EQ(left_out.stats.blobs_not_round, 1);
  EXPECT_EQ(left_out.stats.blobs_used, 5);
  EXPECT_LT(left_out.error_mm, 1e-3);  // five exact rays (float pixels)
  EXPECT_EQ(kept.stats.blobs_not_round, 0);
  EXPECT_EQ(kept.stats.blobs_used, 6);
  EXPECT_GT(kept.error_mm, 10 * left_out.error_mm);
}

// A spot the body hides in part: smaller than the marker's other spots (at their distances) and
// 0.6 px off. With enough whole spots left, the marker's position comes from those alone.
TEST(MarkerStage, APartlyHiddenSpotIsLeftOutOfItsMarkersPosition) {
  const auto cameras = test::marker_ring(6);
  const auto [truth, f] = one_exact_marker(cameras, 8);
  auto run = [&](PartialSpotOptions partial) {
    pipeline::FrameWork w = work_of(f, cameras);
    for (std::size_t c = 0; c < cameras.size(); ++c) {
      blob_t& spot = w.group.blobs[cameras[c].id].blobs.at(0);
      const geometry::ViewRay ray = geometry::view_ray(cameras[c], {spot.x, spot.y});
      const double radius_px = 12.5 / (truth[0] - ray.ray.origin).norm() * ray.pixels_per_rad;
      spot.area = static_cast<float>(3.14159 * radius_px * radius_px);
    }
    blob_t& hidden = w.group.blobs[cameras[2].id].blobs.at(0);
    hidden.area *= 0.6f;
    hidden.x += 0.6f;
    MarkerStageOptions options;
    options.partial_spots = partial;
    MarkerStage stage(cameras, {}, options);
    stage.process(w);
    EXPECT_EQ(w.markers.size(), 1u);
    EXPECT_EQ(w.markers.at(0).camera_ids.size(), 6u);  // every camera that saw it
    return std::pair{(w.markers.at(0).position - truth[0]).norm(), stage.stats()};
  };
  const auto [error_mm, stats] = run({});
  const auto [error_kept_mm, stats_kept] = run({.min_width_ratio = 0, .min_whole_rays = 3});
  EXPECT_EQ(stats.partial_spots_left_out, 1);
  EXPECT_LT(error_mm, 1e-3);  // five exact rays (float pixels)
  EXPECT_EQ(stats_kept.partial_spots_left_out, 0);
  EXPECT_GT(error_kept_mm, 10 * error_mm);
}

// Gives every spot of `w` the threshold area of a whole 25 mm marker at `marker`.
void whole_spot_areas(pipeline::FrameWork& w, const std::vector<sensor::CameraModel>& cameras,
                      const Eigen::Vector3d& marker) {
  for (const sensor::CameraModel& camera : cameras) {
    for (blob_t& spot : w.group.blobs[camera.id].blobs) {
      const geometry::ViewRay ray = geometry::view_ray(camera, {spot.x, spot.y});
      const double radius_px = 12.5 / (marker - ray.ray.origin).norm() * ray.spot_pixels_per_rad;
      spot.area = static_cast<float>(3.14159 * radius_px * radius_px);
    }
  }
}

TEST(MarkerStage, AMergedSpotIsLeftOutOfItsMarker) {
  const auto cameras = test::marker_ring(6);
  const auto [truth, f] = one_exact_marker(cameras, 8);
  pipeline::FrameWork w = work_of(f, cameras);
  whole_spot_areas(w, cameras, truth[0]);
  blob_t& merged = w.group.blobs[cameras[2].id].blobs.at(0);
  merged.area *= 1.9f;  // a neighbour's spot run into it
  merged.x += 0.8f;
  MarkerStage stage(cameras, {});
  stage.process(w);
  ASSERT_EQ(w.markers.size(), 1u);
  EXPECT_EQ(w.markers[0].camera_ids.size(), 5u);
  EXPECT_EQ(
      std::count(w.markers[0].camera_ids.begin(), w.markers[0].camera_ids.end(), cameras[2].id), 0);
  EXPECT_LT((w.markers[0].position - truth[0]).norm(), 1e-3);
  EXPECT_EQ(stage.stats().merged_spots_left_out, 1);
}

// A spot a fifth short of a whole one's area, its centroid moved, stays in its point but weighs
// less; with merged spots off too (the whole spot's width is learnt for both).
TEST(MarkerStage, ASmallerSpotWeighsLessEvenWithMergedSpotsOff) {
  const auto cameras = test::marker_ring(6);
  const auto [truth, f] = one_exact_marker(cameras, 8);
  auto error_mm = [&](double shift) {
    pipeline::FrameWork w = work_of(f, cameras);
    whole_spot_areas(w, cameras, truth[0]);
    blob_t& smaller = w.group.blobs[cameras[2].id].blobs.at(0);
    smaller.area *= 0.8f;  // width ratio 0.89: above the partial spots' 0.85, kept
    smaller.x += 0.6f;
    MarkerStageOptions options;
    options.merged_spots.max_width_ratio = 0;
    options.partial_spots.shift_per_hidden_share = shift;
    MarkerStage stage(cameras, {}, options);
    stage.process(w);
    EXPECT_EQ(w.markers.size(), 1u);
    EXPECT_EQ(w.markers.at(0).camera_ids.size(), 6u);
    return (w.markers.at(0).position - truth[0]).norm();
  };
  EXPECT_LT(error_mm(0.9), 0.8 * error_mm(0));
}

TEST(MarkerStage, ATwoCameraPointWithAMergedSpotIsNoMarker) {
  const auto cameras = test::marker_ring(6);
  const auto [truth, f] = one_exact_marker(cameras, 8);
  MarkerStage stage(cameras, {});
  pipeline::FrameWork learn = work_of(f, cameras);
  whole_spot_areas(learn, cameras, truth[0]);
  stage.process(learn);  // the whole spot's width, from a frame of six whole spots
  ASSERT_EQ(learn.markers.size(), 1u);

  auto two_views = [&](float area_factor) {
    pipeline::FrameWork w = work_of(f, cameras);
    whole_spot_areas(w, cameras, truth[0]);
    for (std::size_t c = 2; c < cameras.size(); ++c) w.group.blobs[cameras[c].id].blobs.clear();
    w.group.blobs[cameras[1].id].blobs.at(0).area *= area_factor;
    stage.process(w);
    return w.markers.size();
  };
  EXPECT_EQ(two_views(1.0f), 1u);
  EXPECT_EQ(two_views(1.9f), 0u);
  EXPECT_EQ(stage.stats().merged_points_dropped, 1);
}

TEST(MarkerMessageStage, ManyMarkersGoOutInPartsWithTheFramesHeader) {
  pipeline::FrameWork w;
  w.group.frame_number = 7;
  w.group.trigger = trigger_t{};
  w.group.trigger->realtime_ns = 1;  // long ago: the latency is large, but measured
  w.ready = std::chrono::steady_clock::now();
  w.cpu_start_us = pipeline::thread_cpu_us();
  for (int i = 0; i < 50; ++i) {
    pipeline::Marker3d m;
    m.id = i;
    m.position = {1.0 * i, 2, 3};
    m.covariance = Eigen::Matrix3d::Identity() * 0.04;
    m.camera_ids = {0, 1};
    w.markers.push_back(m);
  }
  std::vector<marker_frame_t> sent;
  outputs::MarkerMessageStage stage([&](const marker_frame_t& m) { sent.push_back(m); });
  stage.process(w);
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].num_markers, marker_frame_t::MAX_MARKERS);
  EXPECT_EQ(sent[1].total_markers, 50);
  EXPECT_EQ(sent[1].frame_number, 7);
  EXPECT_EQ(sent[0].markers[3].flags, marker_t::FLAG_TWO_CAMERAS);
  EXPECT_FLOAT_EQ(sent[0].markers[3].sigma_y, 0.2f);
  EXPECT_EQ(stage.latency().added(), 1u);
  ASSERT_EQ(stage.host_us().added(), 1u);
  ASSERT_EQ(stage.host_cpu_us().added(), 1u);
  // The host's part since `ready`, in CPU time no more than in wall time (and both small).
  EXPECT_LE(stage.host_cpu_us().values()[0], stage.host_us().values()[0] + 1);
  EXPECT_LT(stage.host_us().values()[0], 1e6);
}

// Markers moving at 1 m/s keep their ids from frame to frame; one hidden for two frames comes back
// with its id, and meanwhile is the tracker's prediction.
TEST(TrackingStage, IdsPersistAndAHiddenMarkerIsPredicted) {
  TrackingStage stage;
  std::map<int, int> id_of_marker;  // marker index -> id
  for (int k = 0; k < 20; ++k) {
    pipeline::FrameWork w;
    w.group.frame_number = k;
    w.group.trigger = trigger_t{};
    w.group.trigger->monotonic_ns = 1'000'000'000 + k * 10'000'000;  // 100 Hz
    w.group.trigger->rate_hz = 100;
    for (int m = 0; m < 3; ++m) {
      if (m == 1 && (k == 10 || k == 11)) continue;  // hidden
      pipeline::Marker3d marker;
      marker.position = Eigen::Vector3d(200.0 * m + 10.0 * k, 0, 1000);
      marker.covariance = Eigen::Matrix3d::Identity() * 0.01;
      marker.camera_ids = {0, 1, 2};
      w.markers.push_back(marker);
    }
    stage.process(w);
    std::size_t measured = 0;
    for (int m = 0; m < 3; ++m) {
      if (m == 1 && (k == 10 || k == 11)) continue;
      const int id = w.markers[measured++].id;
      if (k >= 1) {  // a track is confirmed by its second point
        ASSERT_NE(id, -1) << "frame " << k << " marker " << m;
        if (id_of_marker.contains(m)) {
          EXPECT_EQ(id, id_of_marker[m]) << "frame " << k;
        }
        id_of_marker[m] = id;
      }
    }
    if (k == 10) {
      ASSERT_EQ(w.markers.size(), 3u);
      EXPECT_TRUE(w.markers[2].predicted);
      EXPECT_EQ(w.markers[2].id, id_of_marker[1]);
      EXPECT_NEAR(w.markers[2].position.x(), 300.0, 1.0);
    }
  }
  EXPECT_DOUBLE_EQ(stage.rate_hz(), 100);
}

// A 100 Hz recording replayed with the trigger at 10 Hz: by the trigger's clock a marker moving
// 3 m/s seems to move 0.3 m/s; timed by its frame numbers at 100 Hz it moves as it did.
TEST(TrackingStage, AFixedFrameRateTimesFramesByTheirNumbers) {
  auto speed_mm_s = [](double frame_rate_hz) {
    TrackingStage stage({}, nullptr, frame_rate_hz);
    for (int k = 0; k < 10; ++k) {
      pipeline::FrameWork w;
      w.group.frame_number = 500 + k;
      w.group.trigger = trigger_t{};
      w.group.trigger->monotonic_ns = 1'000'000'000 + k * 100'000'000;  // paced at 10 Hz
      w.group.trigger->rate_hz = 10;
      pipeline::Marker3d marker;
      marker.position = Eigen::Vector3d(30.0 * k, 0, 1000);  // 30 mm a frame
      marker.covariance = Eigen::Matrix3d::Identity() * 0.01;
      marker.camera_ids = {0, 1, 2};
      w.markers.push_back(marker);
      stage.process(w);
    }
    EXPECT_EQ(stage.tracker().tracks().size(), 1u);
    return stage.tracker().tracks().at(0).velocity_mm_s.x();
  };
  EXPECT_NEAR(speed_mm_s(0), 300, 5);      // the trigger's clock
  EXPECT_NEAR(speed_mm_s(100), 3000, 50);  // the frames' own rate
}

}  // namespace
}  // namespace syncap::reconstruction
