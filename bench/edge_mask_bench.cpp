// Classifying one 1280x1024 grey frame: the medi-picture model (interval test, NCC shadow test,
// closing, small components; the thesis' parameters) against OpenCV's MOG2 apply on the same
// frame, in the same process; the defaults (the edge's) likewise; the defaults with and without
// their illumination correction (least-squares matching, eqs 5.12-5.20), and inside a search
// region against the whole frame; and training on 30
// frames of 640x480 against the per-pixel nth_element of eq 5.5's definition; and the person's
// image patch (proto/image_patch.hpp) against masking the frame.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>

#include "syncap/proto/image_patch.hpp"
#include "syncap/segmentation/medi_picture.hpp"

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
  syncap::segmentation::MediPictureOptions options = syncap::segmentation::thesis_masking_options();
  options.remove_shadows = state.range(0) != 0;
  syncap::segmentation::MediPicture medi(syncap::segmentation::train_medi_picture(training),
                                         options);
  const cv::Mat frame = frame_with_person();
  for (auto _ : state) benchmark::DoNotOptimize(medi.apply(frame).data);
}
// scripts/bench.sh pairs "<name>/ours" with "<name>/baseline".
BENCHMARK(BM_MediPicture)->Arg(1)->Name("mask-vs-mog2/ours")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MediPicture)
    ->Arg(0)
    ->Name("mask-without-shadow-test-vs-mog2/ours")
    ->Unit(benchmark::kMillisecond);

// The defaults; range(0) = 0 turns their illumination correction off.
void BM_DefaultMask(benchmark::State& state) {
  const std::vector<cv::Mat> training = empty_scene(20);
  syncap::segmentation::MediPictureOptions options;
  options.correct_illumination = state.range(0) != 0;
  syncap::segmentation::MediPicture medi(
      syncap::segmentation::train_medi_picture(training, options), options);
  const cv::Mat frame = frame_with_person();
  for (auto _ : state) benchmark::DoNotOptimize(medi.apply(frame).data);
}
BENCHMARK(BM_DefaultMask)->Arg(1)->Name("default-mask-vs-mog2/ours")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DefaultMask)
    ->Arg(1)
    ->Name("illumination-correction-vs-none/ours")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DefaultMask)
    ->Arg(0)
    ->Name("illumination-correction-vs-none/baseline")
    ->Unit(benchmark::kMillisecond);

// The defaults inside the tracked body's search region (the person's bounding box grown by
// 40 px, as `syncap regions` draws it after a fit) against the whole frame; with the refresh of
// the shadow's factor every tenth frame (the whole frame then) included, as the edge runs it.
void BM_SearchRegion(benchmark::State& state) {
  const std::vector<cv::Mat> training = empty_scene(20);
  syncap::segmentation::MediPictureOptions options;
  if (state.range(0) != 0) {
    const cv::Rect person(640 - 120 - 40, 500 - 380 - 40, 2 * 160, 2 * 420);
    options.search_polygon = {
        person.tl(), {person.br().x, person.y}, person.br(), {person.x, person.br().y}};
  }
  syncap::segmentation::MediPicture medi(
      syncap::segmentation::train_medi_picture(training, options), options);
  const cv::Mat frame = frame_with_person();
  for (auto _ : state) benchmark::DoNotOptimize(medi.apply(frame).data);
}
BENCHMARK(BM_SearchRegion)
    ->Arg(1)
    ->Name("search-region-vs-whole-frame/ours")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SearchRegion)
    ->Arg(0)
    ->Name("search-region-vs-whole-frame/baseline")
    ->Unit(benchmark::kMillisecond);

std::vector<cv::Mat> training_frames() {
  cv::RNG rng(3);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 30; ++i) {
    cv::Mat frame(480, 640, CV_8UC1);
    rng.fill(frame, cv::RNG::NORMAL, 110, 4);
    frames.push_back(frame);
  }
  return frames;
}

void BM_Training(benchmark::State& state) {
  const std::vector<cv::Mat> frames = training_frames();
  for (auto _ : state) {
    benchmark::DoNotOptimize(syncap::segmentation::train_medi_picture(frames).median.data);
  }
}
BENCHMARK(BM_Training)->Name("train-vs-nth-element/ours")->Unit(benchmark::kMillisecond);

// Eq 5.5 pixel by pixel: two nth_element per pixel (median, MAD), then m, n, d.
void BM_TrainingPerPixel(benchmark::State& state) {
  const std::vector<cv::Mat> frames = training_frames();
  const std::size_t n = frames.size();
  std::vector<uchar> samples(n);
  for (auto _ : state) {
    syncap::segmentation::MediPictureModel model;
    for (cv::Mat* image :
         {&model.median, &model.sigma, &model.minimum, &model.maximum, &model.max_difference}) {
      image->create(frames[0].size(), CV_32FC1);
    }
    for (int y = 0; y < frames[0].rows; ++y) {
      for (int x = 0; x < frames[0].cols; ++x) {
        for (std::size_t z = 0; z < n; ++z) samples[z] = frames[z].at<uchar>(y, x);
        std::vector<uchar> sorted = samples;
        const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(n / 2);
        std::nth_element(sorted.begin(), middle, sorted.end());
        const float median = *middle;
        for (uchar& v : sorted) v = static_cast<uchar>(std::abs(static_cast<float>(v) - median));
        std::nth_element(sorted.begin(), middle, sorted.end());
        const float sigma = 1.4826f * static_cast<float>(*middle);
        float low = 255, high = 0, step = 0;
        bool before = false;
        for (std::size_t z = 0; z < n; ++z) {
          const float v = samples[z];
          const bool stationary = std::abs(v - median) <= 2 * sigma;
          if (stationary) {
            low = std::min(low, v);
            high = std::max(high, v);
            if (before) step = std::max(step, std::abs(v - static_cast<float>(samples[z - 1])));
          }
          before = stationary;
        }
        model.median.at<float>(y, x) = median;
        model.sigma.at<float>(y, x) = sigma;
        model.minimum.at<float>(y, x) = low;
        model.maximum.at<float>(y, x) = high;
        model.max_difference.at<float>(y, x) = step;
      }
    }
    benchmark::DoNotOptimize(model.median.data);
  }
}
BENCHMARK(BM_TrainingPerPixel)
    ->Name("train-vs-nth-element/baseline")
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
BENCHMARK(BM_Mog2)->Name("default-mask-vs-mog2/baseline")->Unit(benchmark::kMillisecond);

}  // namespace

// An image patch of the person (issue 21: the grey values the host's surface matching needs,
// every Nth frame) against masking the same frame with the defaults: what sending a patch adds
// to that frame's work on the board.
void BM_ImagePatch(benchmark::State& state) {
  const std::vector<cv::Mat> training = empty_scene(20);
  const syncap::segmentation::MediPictureOptions options;
  syncap::segmentation::MediPicture medi(
      syncap::segmentation::train_medi_picture(training, options), options);
  const cv::Mat mask = medi.apply(frame_with_person()).clone();
  // Clothes with texture: uniform noise of 0..40 DN over the person (PNG's worst case).
  cv::Mat frame = frame_with_person(), texture(frame.size(), CV_8UC1);
  cv::RNG rng(3);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 40);
  cv::subtract(frame, texture, frame, mask);
  std::size_t bytes = 0, parts = 0;
  for (auto _ : state) {
    const auto patch = syncap::proto::encode_image_patch(1, 30, frame, mask);
    parts = patch.size();
    bytes = 0;
    for (const auto& p : patch) bytes += p.data.size();
  }
  state.counters["parts"] = static_cast<double>(parts);
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_ImagePatch)->Name("patch-vs-mask/ours")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DefaultMask)->Arg(1)->Name("patch-vs-mask/baseline")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
