// Blob detection speed (scripts/bench.sh prints the ratios). Each comparison registers
// "<comparison>/ours" and "<comparison>/baseline", run in the same process:
//   blobs-full-vs-opencv    ours on a full 1280x1024 Mono8 frame with 16 markers vs threshold +
//                           cv::connectedComponentsWithStats + per-blob moments (goal >= 4)
//   blobs-windowed-vs-full  BlobTracker in steady state (windows only) vs our full-frame scan
//                           (goal >= 20)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "detection/blob_detector.hpp"
#include "detection/blob_tracker.hpp"

namespace {

using syncap::blob_t;
using namespace syncap::edge;

// 16 markers of radius 3-6 px (4x4 grid, jittered) on 20 DN, blending to 200 DN, noise 2 DN.
cv::Mat make_frame(uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat1d value(1024, 1280, 20.0);
  cv::RNG place(42);  // the same markers in every frame; only the noise differs
  for (int i = 0; i < 16; ++i) {
    const double cx = 160 + 320 * (i % 4) + place.uniform(-60.0, 60.0);
    const double cy = 128 + 256 * (i / 4) + place.uniform(-60.0, 60.0);
    const double r = place.uniform(3.0, 6.0);
    constexpr int kS = 8;
    for (int y = static_cast<int>(cy - r - 1); y <= cy + r + 1; ++y) {
      for (int x = static_cast<int>(cx - r - 1); x <= cx + r + 1; ++x) {
        int inside = 0;
        for (int sy = 0; sy < kS; ++sy) {
          for (int sx = 0; sx < kS; ++sx) {
            const double dx = x - 0.5 + (sx + 0.5) / kS - cx, dy = y - 0.5 + (sy + 0.5) / kS - cy;
            inside += dx * dx + dy * dy <= r * r;
          }
        }
        value(y, x) += 180.0 * inside / (kS * kS);
      }
    }
  }
  cv::Mat1d noise(value.size());
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
  value += noise;
  cv::Mat image;
  value.convertTo(image, CV_8U);
  return image;
}

const cv::Mat& frame(int i) {
  static const cv::Mat frames[2] = {make_frame(1), make_frame(2)};
  return frames[i & 1];
}

// The baseline: the detector syncap had before (OpenCV threshold, connectedComponentsWithStats,
// then per blob the intensity-weighted centroid over its grown box above the ring median).
std::vector<blob_t> opencv_baseline(const cv::Mat& image, int threshold, int margin) {
  cv::Mat mask, labels, stats, centroids;
  cv::threshold(image, mask, threshold - 1, 255, cv::THRESH_BINARY);
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<blob_t> blobs;
  const cv::Rect inside(0, 0, image.cols, image.rows);
  for (int label = 1; label < n; ++label) {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < 2) continue;
    const cv::Rect box(
        stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
        stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    const cv::Rect w =
        cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin) &
        inside;
    std::vector<uint8_t> ring;
    for (int x = w.x - 1; x <= w.x + w.width; ++x) {
      for (int y : {w.y - 1, w.y + w.height}) {
        if (inside.contains({x, y})) ring.push_back(image.at<uint8_t>(y, x));
      }
    }
    for (int y = w.y; y < w.y + w.height; ++y) {
      for (int x : {w.x - 1, w.x + w.width}) {
        if (inside.contains({x, y})) ring.push_back(image.at<uint8_t>(y, x));
      }
    }
    std::nth_element(ring.begin(), ring.begin() + static_cast<long>(ring.size() / 2), ring.end());
    const double background = ring.empty() ? 0.0 : ring[ring.size() / 2];
    double sw = 0, sx = 0, sy = 0;
    for (int y = w.y; y < w.y + w.height; ++y) {
      for (int x = w.x; x < w.x + w.width; ++x) {
        const int l = labels.at<int>(y, x);
        if (l != label && l != 0) continue;
        const double v = image.at<uint8_t>(y, x) - background;
        if (v <= 0) continue;
        sw += v;
        sx += v * x;
        sy += v * y;
      }
    }
    blob_t b{};
    b.x = static_cast<float>(sx / sw);
    b.y = static_cast<float>(sy / sw);
    b.area = static_cast<float>(area);
    blobs.push_back(b);
  }
  return blobs;
}

void ours_full(benchmark::State& state) {
  BlobDetector detector;
  int i = 0;
  for (auto _ : state) {
    const auto& blobs = detector.detect(frame(i++));
    if (blobs.size() != 16) state.SkipWithError("expected 16 blobs");
    benchmark::DoNotOptimize(blobs.data());
  }
}

void opencv_full(benchmark::State& state) {
  int i = 0;
  for (auto _ : state) {
    const auto blobs = opencv_baseline(frame(i++), 128, 3);
    if (blobs.size() != 16) state.SkipWithError("expected 16 blobs");
    benchmark::DoNotOptimize(blobs.data());
  }
}

void ours_windowed(benchmark::State& state) {
  BlobTrackerConfig config;
  config.full_scan_every = 1 << 30;  // steady state: windows only after the first frame
  BlobTracker tracker(config);
  tracker.process(frame(0));
  int i = 1;
  for (auto _ : state) {
    const auto& blobs = tracker.process(frame(i++));
    if (blobs.size() != 16 || tracker.last_was_full_scan()) {
      state.SkipWithError("expected 16 blobs found in windows");
    }
    benchmark::DoNotOptimize(blobs.data());
  }
  state.counters["roi_px"] = tracker.next_roi().area();
}

BENCHMARK(ours_full)->Name("blobs-full-vs-opencv/ours")->Unit(benchmark::kMicrosecond);
BENCHMARK(opencv_full)->Name("blobs-full-vs-opencv/baseline")->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_windowed)->Name("blobs-windowed-vs-full/ours")->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_full)->Name("blobs-windowed-vs-full/baseline")->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
