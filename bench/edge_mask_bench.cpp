// Classifying one 1280x1024 grey frame: the medi-picture model (interval test, NCC shadow test,
// closing, small components) against OpenCV's MOG2 apply on the same frame, in the same process.
#include <benchmark/benchmark.h>

#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>

#include "segmentation/medi_picture.hpp"

namespace {

const cv::Size kFrameSize(1280, 1024);

cv::Mat scene(cv::RNG& rng) {
  cv::Mat frame(kFrameSize, CV_8UC1);
  rng.fill(frame, cv::RNG::NORMAL, 110, 4);
  return frame;
}

std::vector<cv::Mat> empty_scene(int count) {
  cv::RNG rng(1);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) frames.push_back(scene(rng));
  return frames;
}

// The empty scene with a person-sized bright region and its darker shadow.
cv::Mat frame_with_person() {
  cv::RNG rng(2);
  cv::Mat frame = scene(rng);
  cv::ellipse(frame, {640, 500}, {120, 380}, 0, 0, 360, cv::Scalar(200), cv::FILLED);
  cv::Mat shadow = frame(cv::Rect(760, 800, 300, 150));
  shadow.convertTo(shadow, CV_8U, 0.6);
  return frame;
}

void BM_MediPicture(benchmark::State& state) {
  const std::vector<cv::Mat> training = empty_scene(20);
  syncap::edge::MediPictureOptions options;
  options.remove_shadows = state.range(0) != 0;
  syncap::edge::MediPicture medi(syncap::edge::train_medi_picture(training), options);
  const cv::Mat frame = frame_with_person();
  for (auto _ : state) benchmark::DoNotOptimize(medi.apply(frame).data);
}
// scripts/bench.sh pairs "<name>/ours" with "<name>/baseline".
BENCHMARK(BM_MediPicture)->Arg(1)->Name("mask-vs-mog2/ours")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MediPicture)
    ->Arg(0)
    ->Name("mask-without-shadow-test-vs-mog2/ours")
    ->Unit(benchmark::kMillisecond);

void BM_Mog2(benchmark::State& state) {
  cv::Ptr<cv::BackgroundSubtractorMOG2> mog2 = cv::createBackgroundSubtractorMOG2();
  for (const cv::Mat& frame : empty_scene(20)) {
    cv::Mat mask;
    mog2->apply(frame, mask);
  }
  const cv::Mat frame = frame_with_person();
  cv::Mat mask;
  // learningRate 0 keeps the model as trained, so each iteration sees the same state.
  for (auto _ : state) {
    mog2->apply(frame, mask, 0.0);
    benchmark::DoNotOptimize(mask.data);
  }
}
BENCHMARK(BM_Mog2)->Name("mask-vs-mog2/baseline")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Mog2)
    ->Name("mask-without-shadow-test-vs-mog2/baseline")
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
