#include "matching/marker_matcher.hpp"

#include <gtest/gtest.h>

#include <map>
#include <numeric>
#include <set>

#include "matching/brute_force_matcher.hpp"
#include "synthetic_markers.hpp"

namespace syncap::matching {
namespace {

struct Score {
  long visible = 0;  // markers seen by two or more cameras
  long found = 0;    // of those, with a point made of their blobs only
  long ghosts = 0;   // points mixing markers, or made of spurious blobs
  long points = 0;
  long wrong_rays = 0;           // blobs of another marker (or none) in a found marker's point
  double squared_error_sum = 0;  // of the found points, mm^2
  double mahalanobis_sum = 0;    // their errors normalised by their covariance (mean 3 if right)
  double rms_mm() const { return found > 0 ? std::sqrt(squared_error_sum / found) : 0; }
};

// A point is marker m's when at least two of its blobs are m's and they are the majority; its
// other blobs are wrong rays. Any other point is a ghost.
void score(const test::MarkerFrame& f, const MatchResult& r, Score& s) {
  std::map<int, int> views;
  for (const auto& camera : f.marker_of_blob)
    for (const int m : camera)
      if (m >= 0) ++views[m];
  for (const auto& [m, n] : views) s.visible += n >= 2;
  std::set<int> found;
  for (const MatchedPoint& p : r.points) {
    ++s.points;
    std::map<int, int> votes;
    for (const BlobRef b : p.blobs)
      ++votes[f.marker_of_blob[static_cast<std::size_t>(b.camera)]
                              [static_cast<std::size_t>(b.blob)]];
    const auto best =
        std::max_element(votes.begin(), votes.end(),
                         [](const auto& x, const auto& y) { return x.second < y.second; });
    const int m = best->first;
    if (m < 0 || best->second < 2 || 2 * best->second <= static_cast<int>(p.blobs.size()) ||
        found.contains(m)) {
      ++s.ghosts;
      continue;
    }
    found.insert(m);
    ++s.found;
    s.wrong_rays += static_cast<long>(p.blobs.size()) - best->second;
    const Eigen::Vector3d e = p.point.position - f.markers[static_cast<std::size_t>(m)];
    s.squared_error_sum += e.squaredNorm();
    s.mahalanobis_sum += e.dot(p.point.covariance.ldlt().solve(e));
  }
}

TEST(MarkerMatcher, ExactBlobsGiveEveryMarkerAndNothingElse) {
  const auto cameras = test::marker_ring();
  std::mt19937 rng(11);
  test::MarkerFrameOptions o;
  o.noise_px = 0;
  o.hidden = 0;
  o.spurious_per_camera = 0;
  const test::MarkerFrame f = test::observe(cameras, test::random_markers(rng, 32), o, rng);
  const MatchResult r = MarkerMatcher(cameras).match(f.blobs);
  Score s;
  score(f, r, s);
  EXPECT_EQ(s.visible, 32);
  EXPECT_EQ(s.found, 32);
  EXPECT_EQ(s.ghosts, 0);
  EXPECT_LT(s.rms_mm(), 1e-3);
  for (const MatchedPoint& p : r.points) EXPECT_GE(p.blobs.size(), 2u);
}

// The figures on synthetic frames with exact truth: 8 cameras x 32 markers, 0.15 px
// centroid noise, 15 % of the views hidden, 3 reflections per camera.
TEST(MarkerMatcher, NoisyOccludedFramesWithReflectionsMeetTheFigures) {
  const auto cameras = test::marker_ring();
  MatchOptions options;
  options.volume =
      Eigen::AlignedBox3d(Eigen::Vector3d(-1000, -1000, 0), Eigen::Vector3d(1000, 1000, 2000));
  const MarkerMatcher matcher(cameras, options);
  std::mt19937 rng(5);
  Score s;
  for (int frame = 0; frame < 100; ++frame) {
    const test::MarkerFrame f =
        test::observe(cameras, test::random_markers(rng, 32), test::MarkerFrameOptions{}, rng);
    score(f, matcher.match(f.blobs), s);
  }
  const double found = static_cast<double>(s.found) / static_cast<double>(s.visible);
  const double ghosts = static_cast<double>(s.ghosts) / static_cast<double>(s.points);
  std::cout << "100 frames: " << s.found << " of " << s.visible << " visible markers found ("
            << 100 * found << " %), " << s.ghosts << " ghosts of " << s.points << " points ("
            << 100 * ghosts << " %), " << s.wrong_rays << " wrong rays, 3D RMS " << s.rms_mm()
            << " mm\n";
  EXPECT_GE(found, 0.995);
  EXPECT_LE(ghosts, 0.005);
  // 0.15 px at 4 m through ~7 rays of a ring: ~0.58 mm is the precision the geometry allows; the
  // covariances say so (their normalised squared errors average 3).
  EXPECT_LE(s.rms_mm(), 0.65);
  EXPECT_NEAR(s.mahalanobis_sum / static_cast<double>(s.found), 3.0 * 0.15 * 0.15 / (0.2 * 0.2),
              0.3);
}

// Without the volume, reflections whose rays cross by chance somewhere in the room become ghosts
// (two-camera points, flagged): the volume is what removes them.
TEST(MarkerMatcher, WithoutTheVolumeChanceCrossingsOfReflectionsAreGhosts) {
  const auto cameras = test::marker_ring();
  const MarkerMatcher matcher(cameras);
  std::mt19937 rng(5);
  Score s;
  for (int frame = 0; frame < 100; ++frame) {
    const test::MarkerFrame f =
        test::observe(cameras, test::random_markers(rng, 32), test::MarkerFrameOptions{}, rng);
    score(f, matcher.match(f.blobs), s);
  }
  EXPECT_GE(s.found, s.visible * 995 / 1000);
  EXPECT_GT(s.ghosts, 0) << "no chance crossings: the test lost its reflections";
  EXPECT_LE(static_cast<double>(s.ghosts) / static_cast<double>(s.points), 0.015);
}

TEST(MarkerMatcher, TheCamerasOrderChangesNothing) {
  auto cameras = test::marker_ring();
  std::mt19937 rng(8);
  const test::MarkerFrame f =
      test::observe(cameras, test::random_markers(rng, 32), test::MarkerFrameOptions{}, rng);
  const MatchResult forward = MarkerMatcher(cameras).match(f.blobs);
  std::vector<std::size_t> order(cameras.size());
  std::iota(order.rbegin(), order.rend(), 0);  // reversed
  std::vector<sensor::CameraModel> reversed_cameras;
  std::vector<std::vector<Eigen::Vector2d>> reversed_blobs;
  for (const std::size_t i : order) {
    reversed_cameras.push_back(cameras[i]);
    reversed_blobs.push_back(f.blobs[i]);
  }
  const MatchResult backward = MarkerMatcher(reversed_cameras).match(reversed_blobs);
  ASSERT_EQ(forward.points.size(), backward.points.size());
  std::set<std::vector<std::pair<int, int>>> a, b;
  for (const auto& p : forward.points) {
    std::vector<std::pair<int, int>> key;
    for (const BlobRef& r : p.blobs)
      key.emplace_back(cameras[static_cast<std::size_t>(r.camera)].id, r.blob);
    std::sort(key.begin(), key.end());
    a.insert(key);
  }
  for (const auto& p : backward.points) {
    std::vector<std::pair<int, int>> key;
    for (const BlobRef& r : p.blobs)
      key.emplace_back(reversed_cameras[static_cast<std::size_t>(r.camera)].id, r.blob);
    std::sort(key.begin(), key.end());
    b.insert(key);
  }
  EXPECT_EQ(a, b);
}

// A second method: the brute force finds the same markers (it is the benchmark's baseline).
TEST(MarkerMatcher, TheBruteForceFindsTheSameMarkers) {
  const auto cameras = test::marker_ring(6);
  std::mt19937 rng(21);
  Score ours, theirs;
  for (int frame = 0; frame < 5; ++frame) {
    test::MarkerFrameOptions o;
    o.markers = 16;
    const test::MarkerFrame f = test::observe(cameras, test::random_markers(rng, 16), o, rng);
    score(f, MarkerMatcher(cameras).match(f.blobs), ours);
    score(f, match_by_brute_force(cameras, f.blobs), theirs);
  }
  EXPECT_EQ(ours.visible, theirs.visible);
  EXPECT_GE(ours.found, theirs.found);
  EXPECT_LE(ours.ghosts, theirs.ghosts + 1);
  EXPECT_GE(theirs.found, theirs.visible * 99 / 100);
}

TEST(MarkerMatcher, PointsSeenByTwoCamerasAreFlagged) {
  const auto cameras = test::marker_ring(2);
  std::mt19937 rng(2);
  test::MarkerFrameOptions o;
  o.hidden = 0;
  o.spurious_per_camera = 0;
  const test::MarkerFrame f = test::observe(cameras, test::random_markers(rng, 4), o, rng);
  const MatchResult r = MarkerMatcher(cameras).match(f.blobs);
  ASSERT_FALSE(r.points.empty());
  for (const MatchedPoint& p : r.points) {
    EXPECT_TRUE(p.two_cameras_only());
    EXPECT_EQ(p.camera_mask(), 0b11u);
  }
}

TEST(MarkerMatcher, NoBlobsOrOneCameraGiveNoPoints) {
  const auto cameras = test::marker_ring(3);
  EXPECT_TRUE(MarkerMatcher(cameras).match({}).points.empty());
  EXPECT_TRUE(MarkerMatcher(cameras).match({{{100, 100}, {200, 300}}}).points.empty());
}

}  // namespace
}  // namespace syncap::matching
