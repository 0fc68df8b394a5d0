// A dense real-size marker set through the live host's whole marker chain (issue #38, "Speed"):
// one group of 8 cameras x 55 markers moving as a body does at 100 Hz, 10 of them in pairs 25 mm
// apart (a dense trunk and hand set), each spot with its threshold area, spots closer than their
// radii merged into one blob as the edge would report it, 3 reflections per camera and 15 % of
// the views hidden, through the marker stage (matching, triangulation, partly hidden and merged
// spots) and the tracking stage; against the brute force (every blob pair of every camera pair
// triangulated and checked in all other cameras) on the same groups. scripts/bench.sh prints
// "markers-8cam-55-dense-vs-bruteforce: R x"; goal R >= 10 and <= 1 ms per group.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "matching/brute_force_matcher.hpp"
#include "reconstruction/marker_stage.hpp"
#include "reconstruction/tracking_stage.hpp"
#include "synthetic_markers.hpp"

namespace {

using syncap::blob_t;
using syncap::pipeline::FrameWork;
namespace test = syncap::test;

constexpr int kMarkers = 55, kPairs = 5, kFrames = 100;
constexpr double kRateHz = 100, kMarkerRadiusMm = 9.5;

// The set at rest: 45 markers spread over the volume, 5 pairs 25 mm apart.
std::vector<Eigen::Vector3d> marker_set(std::mt19937& rng) {
  std::vector<Eigen::Vector3d> set = test::random_markers(rng, kMarkers - kPairs);
  for (int p = 0; p < kPairs; ++p)
    set.push_back(set[static_cast<std::size_t>(p)] + Eigen::Vector3d(25, 0, 0));
  return set;
}

// Spots of one camera: each marker's disc, those that touch run into one blob (area-weighted
// centroid, summed area), as the edge's connected components would.
std::vector<blob_t> spots(const syncap::sensor::CameraModel& camera,
                          const std::vector<Eigen::Vector3d>& markers,
                          const std::vector<Eigen::Vector2d>& seen) {
  struct Disc {
    Eigen::Vector2d centre;
    double radius = 0;
  };
  std::vector<Disc> discs;
  for (const Eigen::Vector2d& pixel : seen) {
    double nearest = 1e9;  // the marker this spot is of: the one projecting nearest
    for (const Eigen::Vector3d& m : markers) {
      const auto p = camera.project(m);
      if (!p.ok() || (p.pixel - pixel).norm() > 1.0) continue;
      nearest = std::min(nearest, (m - camera.projection_centre()).norm());
    }
    const double distance = nearest < 1e9 ? nearest : 4000;  // a reflection: as a marker's
    const double scale = syncap::geometry::view_ray(camera, pixel).spot_pixels_per_rad;
    discs.push_back({pixel, kMarkerRadiusMm / distance * scale});
  }
  std::vector<blob_t> blobs;
  std::vector<bool> used(discs.size(), false);
  for (std::size_t i = 0; i < discs.size(); ++i) {
    if (used[i]) continue;
    double area = std::numbers::pi * discs[i].radius * discs[i].radius;
    Eigen::Vector2d weighted = area * discs[i].centre;
    double total = area;
    for (std::size_t j = i + 1; j < discs.size(); ++j) {
      if (used[j] || (discs[j].centre - discs[i].centre).norm() > discs[i].radius + discs[j].radius)
        continue;
      used[j] = true;
      area = std::numbers::pi * discs[j].radius * discs[j].radius;
      weighted += area * discs[j].centre;
      total += area;
    }
    blob_t b{};
    b.x = static_cast<float>(weighted.x() / total);
    b.y = static_cast<float>(weighted.y() / total);
    b.area = static_cast<float>(total);
    blobs.push_back(b);
  }
  return blobs;
}

// 100 frames of the set swaying 60 mm at 1.3 Hz, one frame group each.
const std::vector<FrameWork>& groups() {
  static const std::vector<FrameWork> frames = [] {
    std::mt19937 rng(7);
    const auto cameras = test::marker_ring(8);
    const std::vector<Eigen::Vector3d> rest = marker_set(rng);
    std::vector<FrameWork> out;
    for (int k = 0; k < kFrames; ++k) {
      const double t = k / kRateHz;
      std::vector<Eigen::Vector3d> now = rest;
      for (std::size_t m = 0; m < now.size(); ++m)
        now[m] += 60 * std::sin(2 * std::numbers::pi * 1.3 * t + 0.1 * static_cast<double>(m)) *
                  Eigen::Vector3d(1, 0.5, 0.2);
      const test::MarkerFrame f = test::observe(cameras, now, test::MarkerFrameOptions{}, rng);
      FrameWork w;
      w.group.frame_number = k;
      for (std::size_t c = 0; c < cameras.size(); ++c) {
        syncap::blob_frame_t b{};
        b.camera_id = static_cast<int16_t>(cameras[c].id);
        b.frame_number = k;
        b.blobs = spots(cameras[c], now, f.blobs[c]);
        b.num_blobs = static_cast<int16_t>(b.blobs.size());
        w.group.blobs[cameras[c].id] = b;
      }
      out.push_back(std::move(w));
    }
    return out;
  }();
  return frames;
}

syncap::matching::MatchOptions volume_options() {
  syncap::matching::MatchOptions o;
  o.volume =
      Eigen::AlignedBox3d(Eigen::Vector3d(-1100, -1100, 0), Eigen::Vector3d(1100, 1100, 2000));
  return o;
}

void BM_Ours(benchmark::State& state) {
  syncap::reconstruction::MarkerStage markers(test::marker_ring(8), volume_options());
  syncap::reconstruction::TrackingStage tracking({}, nullptr, kRateHz);
  groups();  // made once, before the clock runs
  std::size_t i = 0;
  int64_t loop = 0;  // replayed in a loop, 1000 frames apart: the old tracks end
  for (auto _ : state) {
    FrameWork w = groups()[i];
    w.group.frame_number += loop;
    markers.process(w);
    tracking.process(w);
    benchmark::DoNotOptimize(w.markers.data());
    if (++i == groups().size()) {
      i = 0;
      loop += 1000;
    }
  }
}
BENCHMARK(BM_Ours)->Name("markers-8cam-55-dense-vs-bruteforce/ours")->Unit(benchmark::kMicrosecond);

void BM_BruteForce(benchmark::State& state) {
  const auto cameras = test::marker_ring(8);
  const auto options = volume_options();
  std::vector<std::vector<std::vector<Eigen::Vector2d>>> pixels;
  for (const FrameWork& w : groups()) {
    pixels.emplace_back();
    for (const auto& [id, frame] : w.group.blobs) {
      pixels.back().emplace_back();
      for (const blob_t& b : frame.blobs) pixels.back().back().emplace_back(b.x, b.y);
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        syncap::matching::match_by_brute_force(cameras, pixels[i++ % pixels.size()], options));
  }
}
BENCHMARK(BM_BruteForce)
    ->Name("markers-8cam-55-dense-vs-bruteforce/baseline")
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
