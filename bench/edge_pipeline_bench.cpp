// CPU time of syncap-edge's per-frame work at 1280x1024, as EdgeNode::on_trigger does it on a
// board: copy the camera buffer, detect the blobs, (with --mode both) the medi-picture mask and
// its contours, encode the messages. Publishing is a no-op here (on a board it is the publishing
// queue's thread). Prints per mode the mean CPU ms per frame of the calling thread and the share
// of one core that costs at 30 Hz:
//
//   ninja -C build bench_edge_pipeline && build/bin/bench_edge_pipeline
//
// Frames: a lit room (a 16 px checkerboard, 60..150 DN, noise 2 DN), a person-sized bright
// ellipse that moves between frames, 16 retro-reflective markers (radius 3-6 px, 250 DN) on and
// around the person, 8 different frames in turn: what the replay bench renders, at the thesis'
// camera size.
#include <benchmark/benchmark.h>

#include <ctime>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "app/edge_node.hpp"

namespace {

using namespace syncap::edge;

const cv::Size kSensor(1280, 1024);
constexpr int kFrames = 8;
constexpr int kTrainingFrames = 20;

cv::Mat room(cv::RNG& rng) {
  cv::Mat1f value(kSensor);
  for (int y = 0; y < kSensor.height; ++y) {
    for (int x = 0; x < kSensor.width; ++x) value(y, x) = 60.0f + 90.0f * ((x / 16 + y / 16) % 2);
  }
  cv::Mat1f noise(kSensor);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
  value += noise;
  cv::Mat image;
  value.convertTo(image, CV_8U);
  return image;
}

// Frame i of the person phase: the person at a place of its own, the markers on it.
cv::Mat person_frame(int i) {
  cv::RNG rng(static_cast<uint64_t>(100 + i));
  cv::Mat image = room(rng);
  const cv::Point centre(500 + 30 * i, 520);
  cv::ellipse(image, centre, {110, 360}, 0, 0, 360, cv::Scalar(185), cv::FILLED);
  cv::RNG place(static_cast<uint64_t>(7 + i));
  for (int m = 0; m < 16; ++m) {
    const cv::Point at(centre.x + place.uniform(-160, 160), centre.y + place.uniform(-400, 400));
    cv::circle(image, at, place.uniform(3, 7), cv::Scalar(250), cv::FILLED, cv::LINE_AA);
  }
  return image;
}

// Serves frame k as a camera does: a fresh copy of its buffer.
class BenchSource : public FrameSource {
 public:
  BenchSource() {
    cv::RNG rng(1);
    for (int i = 0; i < kTrainingFrames; ++i) empty_.push_back(room(rng));
    for (int i = 0; i < kFrames; ++i) person_.push_back(person_frame(i));
  }
  std::optional<Frame> grab(int64_t frame_number) override {
    Frame frame;
    frame.frame_number = frame_number;
    frame.image = frame_number < kTrainingFrames ? empty_[frame_number].clone()
                                                 : person_[frame_number % kFrames].clone();
    return frame;
  }
  std::string describe() const override { return "bench frames"; }

 private:
  std::vector<cv::Mat> empty_, person_;
};

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

void BM_EdgePipeline(benchmark::State& state, bool mask) {
  EdgeOptions options;
  options.quiet = true;
  options.detector.threshold = 200;  // the replay bench's: targets above the lit room
  options.mask = mask;
  options.train_frames = mask ? kTrainingFrames : 0;
  BenchSource source;
  int64_t blobs = 0, silhouette_parts = 0;
  EdgeNode node(options, source,
                {[&](const syncap::blob_frame_t& f) { blobs += f.num_blobs; },
                 [](const syncap::camera_status_t&) {},
                 [&](const syncap::silhouette_part_t&) { ++silhouette_parts; },
                 {}});
  syncap::trigger_t trigger{};
  for (; trigger.frame_number < kTrainingFrames; ++trigger.frame_number) node.on_trigger(trigger);
  blobs = silhouette_parts = 0;
  const double cpu_start = thread_cpu_s();
  int64_t frames = 0;
  for (auto _ : state) {
    node.on_trigger(trigger);
    ++trigger.frame_number;
    ++frames;
  }
  const double cpu_ms = (thread_cpu_s() - cpu_start) * 1e3 / static_cast<double>(frames);
  state.counters["cpu_ms_per_frame"] = cpu_ms;
  state.counters["core_pct_at_30Hz"] = cpu_ms * 30.0 / 10.0;  // ms per 1000 ms, in %
  state.counters["blobs_per_frame"] = static_cast<double>(blobs) / static_cast<double>(frames);
  state.counters["silhouette_parts_per_frame"] =
      static_cast<double>(silhouette_parts) / static_cast<double>(frames);
}
BENCHMARK_CAPTURE(BM_EdgePipeline, blobs, false)
    ->Name("edge-pipeline/blobs")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EdgePipeline, both, true)
    ->Name("edge-pipeline/both")
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
