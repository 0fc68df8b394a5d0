// The edge's per-frame work for an instruction counter (scripts/count-instructions.sh,
// docs/design/edge.md "Instructions per frame"):
//
//   edge_instructions render DIR            writes the frames of bench_edge_pipeline (raw 8-bit
//                                           1280x1024: 20 of the empty room, 8 with the person)
//   edge_instructions blobs|both K DIR      reads them, trains on 2 empty frames (both), then
//                                           runs EdgeNode::on_trigger on K person frames
//
// Run the second form under a counter with K = 1 and K = 1 + N: the difference over N is the
// instructions of one frame, without the start-up, the reading (one fread a frame, done by
// the kernel) and the training, which both runs share. The frames are made once, natively:
// rendering them would cost far more instructions than processing them. Two training frames
// (the least the model takes) keep the shared part short; a frame's masking costs the same
// whatever the model was learnt from.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/edge_node.hpp"
#include "edge_bench_frames.hpp"

namespace {

using namespace syncap::edge;
constexpr int kTraining = 2;

std::string frame_path(const std::string& dir, const char* kind, int i) {
  return dir + "/" + kind + "_" + std::to_string(i) + ".gray";
}

int render(const std::string& dir) {
  std::filesystem::create_directories(dir);
  cv::RNG rng(1);
  for (int i = 0; i < bench::kTrainingFrames; ++i) {
    const cv::Mat image = bench::room(rng);
    std::FILE* f = std::fopen(frame_path(dir, "empty", i).c_str(), "wb");
    if (!f || std::fwrite(image.data, image.total(), 1, f) != 1) return 1;
    std::fclose(f);
  }
  for (int i = 0; i < bench::kFrames; ++i) {
    const cv::Mat image = bench::person_frame(i);
    std::FILE* f = std::fopen(frame_path(dir, "person", i).c_str(), "wb");
    if (!f || std::fwrite(image.data, image.total(), 1, f) != 1) return 1;
    std::fclose(f);
  }
  return 0;
}

cv::Mat read_frame(const std::string& path) {
  cv::Mat image(bench::kSensor, CV_8UC1);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f || std::fread(image.data, image.total(), 1, f) != 1) {
    std::fprintf(stderr, "edge_instructions: cannot read %s (edge_instructions render DIR)\n",
                 path.c_str());
    std::exit(1);
  }
  std::fclose(f);
  return image;
}

// Serves the frames as a camera does: a fresh copy of its buffer, as bench::BenchSource.
class FileSource : public FrameSource {
 public:
  explicit FileSource(const std::string& dir) {
    for (int i = 0; i < kTraining; ++i) empty_.push_back(read_frame(frame_path(dir, "empty", i)));
    for (int i = 0; i < bench::kFrames; ++i) {
      person_.push_back(read_frame(frame_path(dir, "person", i)));
    }
  }
  std::optional<Frame> grab(int64_t frame_number) override {
    Frame frame;
    frame.frame_number = frame_number;
    frame.image = frame_number < kTraining ? empty_[frame_number].clone()
                                           : person_[frame_number % bench::kFrames].clone();
    return frame;
  }
  std::string describe() const override { return "edge_instructions frames"; }

 private:
  std::vector<cv::Mat> empty_, person_;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "render" && argc == 3) return render(argv[2]);
  const long frames = argc == 4 ? std::strtol(argv[2], nullptr, 10) : 0;
  if ((mode != "blobs" && mode != "both") || frames < 1) {
    std::fprintf(stderr,
                 "usage: edge_instructions render DIR | edge_instructions blobs|both K DIR\n");
    return 2;
  }
  EdgeOptions options;
  options.quiet = true;
  options.detector.threshold = 200;  // as bench_edge_pipeline: targets above the lit room
  options.mask = mode == "both";
  options.train_frames = options.mask ? kTraining : 0;
  FileSource source(argv[3]);
  long blobs = 0, silhouette_parts = 0;
  EdgeNode node(options, source,
                {[&](const syncap::blob_frame_t& f) { blobs += f.num_blobs; },
                 [](const syncap::camera_status_t&) {},
                 [&](const syncap::silhouette_part_t&) { ++silhouette_parts; },
                 {}});
  syncap::trigger_t trigger{};
  if (options.mask) {
    for (; trigger.frame_number < kTraining; ++trigger.frame_number) node.on_trigger(trigger);
  }
  trigger.frame_number = kTraining;  // the person frames
  blobs = silhouette_parts = 0;
  for (long i = 0; i < frames; ++i, ++trigger.frame_number) node.on_trigger(trigger);
  std::fprintf(stderr, "edge_instructions: %s, %ld frames: %ld blobs, %ld silhouette parts\n",
               mode.c_str(), frames, blobs, silhouette_parts);
  return 0;
}
