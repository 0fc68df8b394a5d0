// Blob detection speed (scripts/bench.sh prints the ratios). Each comparison registers
// "<comparison>/ours" and "<comparison>/baseline", run in the same process:
//   blobs-full-vs-opencv    ours on a full 1280x1024 Mono8 frame with 16 markers vs threshold +
//                           cv::connectedComponentsWithStats + per-blob moments (goal >= 4)
//   blobs-windowed-vs-full  BlobTracker in steady state (windows only) vs our full-frame scan
//                           (goal >= 20), both on 2 frames in turn (2.6 MB: they stay cached)
//   blobs-windowed-vs-full-fresh  the same, each frame flushed from every cache
//                           level before it is detected, as a camera's frame that DMA has just
//                           written to memory (both sides read every pixel they need from memory)
//   blobs-windowed-vs-opencv  the windowed steady state vs the OpenCV baseline of the first line
//                           (the two goals above together ask 4 x 20 = 80)
//   blobs-ideal-windows-vs-full  the ceiling of any tracker with this measurement: each blob
//                           measured in the smallest window that holds its centroid window and
//                           background ring (a perfect prediction, no search margin), with no
//                           tracking at all, vs our full-frame scan
// The windowed side first checks that it finds what the full frame finds, to the last bit.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <opencv2/imgproc.hpp>
#include <tuple>
#include <vector>

#include "detection/blob_detector.hpp"
#include "detection/blob_tracker.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// Frame i of a rotation of two (2.6 MB: they stay cached unless flushed).
const cv::Mat& frame(int i) {
  static const cv::Mat frames[2] = {make_frame(1), make_frame(2)};
  return frames[i % 2];
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

void ours_windowed(benchmark::State& state) {
  BlobTrackerConfig config;
  config.full_scan_every = 1 << 30;  // steady state: windows only after the first frame
  BlobTracker tracker(config);
  BlobDetector full;
  tracker.process(frame(0));
  // Let the search margins settle on the tracks' prediction errors, checking the outputs.
  for (int k = 1; k <= 8; ++k) {
    if (!same_blobs(tracker.process(frame(k)), full.detect(frame(k)))) {
      state.SkipWithError("windowed blobs differ from the full frame's");
      return;
    }
  }
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

// Writes back and invalidates the frame's cache lines, as a driver does for a buffer before the
// camera's DMA writes it: its pixels come from memory, while the code, the detector's state and
// the page tables stay as warm as in a process that handles frame after frame.
void flush_from_caches(const cv::Mat& frame) {
  constexpr size_t kLine = 64;
#if defined(__SSE2__)
  for (const uint8_t* p = frame.datastart; p < frame.dataend; p += kLine) _mm_clflush(p);
  _mm_mfence();
#elif defined(__aarch64__)
  for (const uint8_t* p = frame.datastart; p < frame.dataend; p += kLine) {
    asm volatile("dc civac, %0" : : "r"(p) : "memory");
  }
  asm volatile("dsb sy" : : : "memory");
#else
  static const std::vector<uint64_t> junk(4 << 20, 1);  // 32 MB read: evicts everything
  uint64_t sum = 0;
  for (const uint64_t v : junk) sum += v;
  benchmark::DoNotOptimize(sum);
  (void)frame;
#endif
}

// Each iteration flushes the next frame from the caches, then times `detect` on it.
template <class Detect>
void time_fresh_frames(benchmark::State& state, Detect&& detect) {
  int i = 0;
  for (auto _ : state) {
    const cv::Mat& image = frame(i++);
    flush_from_caches(image);
    const auto start = std::chrono::steady_clock::now();
    detect(image);
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(took.count());
  }
}

void ours_full_fresh(benchmark::State& state) {
  BlobDetector detector;
  time_fresh_frames(state, [&](const cv::Mat& image) {
    const auto& blobs = detector.detect(image);
    if (blobs.size() != 16) state.SkipWithError("expected 16 blobs");
    benchmark::DoNotOptimize(blobs.data());
  });
}

// The cache lines (64 bytes) that hold the windows' pixels: what a windowed frame must fetch.
size_t cache_lines_of(const cv::Mat& image, const std::vector<cv::Rect>& windows) {
  constexpr uintptr_t kLine = 64;
  size_t lines = 0;
  for (const cv::Rect& w : windows) {
    for (int y = w.y; y < w.y + w.height; ++y) {
      const auto first = reinterpret_cast<uintptr_t>(image.ptr<uint8_t>(y) + w.x);
      lines += (first + static_cast<uintptr_t>(w.width) - 1) / kLine - first / kLine + 1;
    }
  }
  return lines;
}

void ours_windowed_fresh(benchmark::State& state) {
  BlobTrackerConfig config;
  config.full_scan_every = 1 << 30;  // steady state, as in ours_windowed (whose check covers it)
  BlobTracker tracker(config);
  for (int k = 0; k <= 8; ++k) tracker.process(frame(k));  // the margins settle
  time_fresh_frames(state, [&](const cv::Mat& image) {
    const auto& blobs = tracker.process(image);
    if (blobs.size() != 16 || tracker.last_was_full_scan()) {
      state.SkipWithError("expected 16 blobs found in windows");
    }
    benchmark::DoNotOptimize(blobs.data());
  });
  // The frame's bytes over the windows' lines' bytes: the most a windowed frame could gain where
  // reading memory is all that counts.
  const size_t lines = cache_lines_of(frame(0), tracker.windows());
  state.counters["window_lines"] = static_cast<double>(lines);
  state.counters["frame_per_window_bytes"] = static_cast<double>(frame(0).total()) / (64.0 * lines);
}

// The smallest windows a tracker could search: each blob's box grown by the centroid window's
// margin and the one-pixel background ring. detect_in in them is the per-blob work a windowed
// frame cannot avoid while it measures what the full frame measures.
void ours_ideal_windows(benchmark::State& state) {
  BlobDetector full, windowed;
  const int grow = full.config().window_margin + 1;
  std::vector<cv::Rect> windows;
  for (const blob_t& b : full.detect(frame(0))) {
    windows.emplace_back(b.bbox_x - grow, b.bbox_y - grow, b.bbox_w + 2 * grow,
                         b.bbox_h + 2 * grow);
  }
  const int threshold = full.threshold_for(frame(0));
  std::vector<blob_t> blobs;
  blobs.reserve(windows.size());
  const auto detect = [&](const cv::Mat& image) {
    blobs.clear();
    for (const cv::Rect& w : windows) windowed.detect_in(image, w, threshold, 0, blobs);
  };
  for (int k = 0; k < 2; ++k) {
    detect(frame(k));
    if (!same_blobs(blobs, full.detect(frame(k)))) {
      state.SkipWithError("blobs in the ideal windows differ from the full frame's");
      return;
    }
  }
  int i = 0;
  for (auto _ : state) {
    detect(frame(i++));
    benchmark::DoNotOptimize(blobs.data());
  }
  int pixels = 0;
  for (const cv::Rect& w : windows) pixels += w.area();
  state.counters["window_px"] = pixels;
}

BENCHMARK(ours_full)->Name("blobs-full-vs-opencv/ours")->Unit(benchmark::kMicrosecond);
BENCHMARK(opencv_full)->Name("blobs-full-vs-opencv/baseline")->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_windowed)->Name("blobs-windowed-vs-full/ours")->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_full)->Name("blobs-windowed-vs-full/baseline")->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_windowed)->Name("blobs-windowed-vs-opencv/ours")->Unit(benchmark::kMicrosecond);
BENCHMARK(opencv_full)->Name("blobs-windowed-vs-opencv/baseline")->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_ideal_windows)
    ->Name("blobs-ideal-windows-vs-full/ours")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_full)->Name("blobs-ideal-windows-vs-full/baseline")->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_windowed_fresh)
    ->Name("blobs-windowed-vs-full-fresh/ours")
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(ours_full_fresh)
    ->Name("blobs-windowed-vs-full-fresh/baseline")
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
