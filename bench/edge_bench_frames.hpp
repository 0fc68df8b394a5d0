// The frames of the edge's per-frame benchmarks (bench_edge_pipeline, edge_instructions): a lit
// room (a 16 px checkerboard, 60..150 DN, noise 2 DN), a person-sized bright ellipse that moves
// between frames, 16 retro-reflective markers (radius 3-6 px, 250 DN) on and around the person,
// 8 different frames in turn, at the thesis' camera size (1280x1024); before them 20 frames of
// the empty room to train the masking on.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "sensor/frame_source.hpp"

namespace syncap::edge::bench {

inline const cv::Size kSensor(1280, 1024);
constexpr int kFrames = 8;
constexpr int kTrainingFrames = 20;

inline cv::Mat room(cv::RNG& rng) {
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
inline cv::Mat person_frame(int i) {
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

}  // namespace syncap::edge::bench
