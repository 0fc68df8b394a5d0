// Blob detection speed (scripts/bench.sh prints the ratios). Each comparison registers
// "<comparison>/ours" and "<comparison>/baseline", run in the same process:
//   blobs-full-vs-opencv    ours on a full 1280x1024 Mono8 frame with 16 markers vs threshold +
//                           cv::connectedComponentsWithStats + per-blob moments (goal >= 4)
//   blobs-windowed-vs-full  BlobTracker in steady state (windows only) vs our full-frame scan
//                           (goal >= 20), both on 2 frames in turn (2.6 MB: they stay cached)
//   blobs-windowed-vs-full-cold  the same on 8 frames in turn (10.5 MB, more than the
//                           development machine's 8 MB last-level cache): each frame comes from
//                           memory, as a camera's frame written there by DMA does
// The windowed side first checks that it finds what the full frame finds, to the last bit.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <tuple>
#include <vector>

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

constexpr int kWarmFrames = 2, kColdFrames = 8;

// Frame i of a rotation of `count` frames (kWarmFrames or kColdFrames).
const cv::Mat& frame(int i, int count = kWarmFrames) {
  static const std::vector<cv::Mat> frames = [] {
    std::vector<cv::Mat> f;
    for (int k = 0; k < kColdFrames; ++k) f.push_back(make_frame(static_cast<uint64_t>(k + 1)));
    return f;
  }();
  return frames[static_cast<size_t>(i % count)];
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

void ours_full(benchmark::State& state, int frames) {
  BlobDetector detector;
  int i = 0;
  for (auto _ : state) {
    const auto& blobs = detector.detect(frame(i++, frames));
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

// The windows must give what the full frame gives, blob for blob (ties of area may be ordered
// differently: compared in raster order).
bool same_blobs(std::vector<blob_t> windowed, std::vector<blob_t> full) {
  if (windowed.size() != full.size()) return false;
  const auto raster = [](const blob_t& a, const blob_t& b) {
    return std::tie(a.y, a.x) < std::tie(b.y, b.x);
  };
  std::sort(windowed.begin(), windowed.end(), raster);
  std::sort(full.begin(), full.end(), raster);
  for (size_t i = 0; i < full.size(); ++i) {
    const blob_t &a = windowed[i], &b = full[i];
    if (a.x != b.x || a.y != b.y || a.area != b.area || a.peak != b.peak ||
        (a.flags & ~blob_t::FLAG_WINDOWED) != b.flags) {
      return false;
    }
  }
  return true;
}

void ours_windowed(benchmark::State& state, int frames) {
  BlobTrackerConfig config;
  config.full_scan_every = 1 << 30;  // steady state: windows only after the first frame
  BlobTracker tracker(config);
  BlobDetector full;
  tracker.process(frame(0, frames));
  // Let the search margins settle on the tracks' prediction errors, checking the outputs.
  for (int k = 1; k <= 8; ++k) {
    if (!same_blobs(tracker.process(frame(k, frames)), full.detect(frame(k, frames)))) {
      state.SkipWithError("windowed blobs differ from the full frame's");
      return;
    }
  }
  int i = 1;
  for (auto _ : state) {
    const auto& blobs = tracker.process(frame(i++, frames));
    if (blobs.size() != 16 || tracker.last_was_full_scan()) {
      state.SkipWithError("expected 16 blobs found in windows");
    }
    benchmark::DoNotOptimize(blobs.data());
  }
  state.counters["roi_px"] = tracker.next_roi().area();
}

BENCHMARK_CAPTURE(ours_full, warm, kWarmFrames)
    ->Name("blobs-full-vs-opencv/ours")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(opencv_full)->Name("blobs-full-vs-opencv/baseline")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(ours_windowed, warm, kWarmFrames)
    ->Name("blobs-windowed-vs-full/ours")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(ours_full, warm, kWarmFrames)
    ->Name("blobs-windowed-vs-full/baseline")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(ours_windowed, cold, kColdFrames)
    ->Name("blobs-windowed-vs-full-cold/ours")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(ours_full, cold, kColdFrames)
    ->Name("blobs-windowed-vs-full-cold/baseline")
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
