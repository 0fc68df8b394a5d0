// The edge's vector paths (OpenCV's universal intrinsics: SSE2 on amd64, NEON on arm64) give
// the same bits on every processor: blobs, their shapes, the medi-picture model and masks of
// fixed scenes are hashed and compared with the hash recorded on amd64. The same test runs
// natively (label unit) and under qemu-aarch64 in the arm64 cross build (label emulated,
// scripts/cross-build.sh arm64 --test), so a NEON path that differs in one bit from the SSE2
// path fails on arm64. The scenes are made with integer arithmetic only, so that they are the
// same bits everywhere too. A deliberate change of the detector or the masking changes the
// hashes: record the new ones (the failure prints them) after checking the change natively.
// This test found that GCC fused a * b + c into one instruction on arm64 (one rounding instead
// of two): both hashes differed until the build turned contraction off there (CMakeLists.txt).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include <opencv2/core.hpp>

#include "detection/blob_detector.hpp"
#include "detection/blob_tracker.hpp"
#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::edge {
namespace {

// FNV-1a, 64 bits, over values fed one by one in a fixed byte order.
class Fnv1a {
 public:
  void add_bytes(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 1099511628211ull;
  }
  template <typename T>
  void add(T value) {
    static_assert(std::is_arithmetic_v<T>);
    uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));  // little endian on both processors
    add_bytes(bytes, sizeof(T));
  }
  void add(const cv::Mat& image) {
    for (int y = 0; y < image.rows; ++y) add_bytes(image.ptr(y), image.cols * image.elemSize());
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 14695981039346656037ull;
};

// A linear congruential generator: the same numbers on every platform and library.
class Lcg {
 public:
  explicit Lcg(uint32_t seed) : state_(seed) {}
  uint32_t next(uint32_t bound) {
    state_ = state_ * 1664525u + 1013904223u;
    return (state_ >> 8) % bound;
  }

 private:
  uint32_t state_;
};

// 1280x1024 with a textured, noisy background and 48 discs of radius 1.5-6 px at positions in
// 1/16 px, their rim covered by 4x4 samples a pixel (integers only).
cv::Mat blob_scene(uint32_t seed) {
  Lcg rng(seed);
  cv::Mat image(1024, 1280, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<uint8_t>(y, x) = static_cast<uint8_t>(20 + (x * 7 + y * 13) % 11 + rng.next(8));
    }
  }
  for (int i = 0; i < 48; ++i) {
    const int cx16 = 160 + static_cast<int>(rng.next(1240 * 16 - 320));  // 1/16 px
    const int cy16 = 160 + static_cast<int>(rng.next(984 * 16 - 320));
    const int r16 = 24 + static_cast<int>(rng.next(73));
    const int peak = 120 + static_cast<int>(rng.next(160));  // above 255: saturated
    for (int y = (cy16 - r16) / 16 - 1; y <= (cy16 + r16) / 16 + 1; ++y) {
      for (int x = (cx16 - r16) / 16 - 1; x <= (cx16 + r16) / 16 + 1; ++x) {
        int inside = 0;
        for (int sy = 0; sy < 4; ++sy) {
          for (int sx = 0; sx < 4; ++sx) {
            const int dx = x * 16 + sx * 4 + 2 - cx16, dy = y * 16 + sy * 4 + 2 - cy16;
            inside += dx * dx + dy * dy <= r16 * r16;
          }
        }
        uint8_t& pixel = image.at<uint8_t>(y, x);
        pixel = static_cast<uint8_t>(std::min(255, pixel + peak * inside / 16));
      }
    }
  }
  return image;
}

void add_blobs(Fnv1a& hash, const std::vector<blob_t>& blobs) {
  hash.add(static_cast<uint32_t>(blobs.size()));
  for (const blob_t& b : blobs) {
    hash.add(b.x), hash.add(b.y), hash.add(b.area), hash.add(b.peak);
    hash.add(b.bbox_x), hash.add(b.bbox_y), hash.add(b.bbox_w), hash.add(b.bbox_h);
    hash.add(b.flags);
  }
}

TEST(VectorBits, BlobsOfTheFullFrameAndTheirWindowsAreTheRecordedBits) {
  Fnv1a hash;
  for (uint32_t seed : {1u, 2u, 3u}) {
    const cv::Mat image = blob_scene(seed);
    BlobDetectorConfig config;
    config.threshold = seed == 3 ? 0 : 90;  // the third frame: the automatic threshold
    BlobDetector detector(config);
    const std::vector<blob_t>& blobs = detector.detect(image);
    EXPECT_GE(blobs.size(), 40u) << "seed " << seed;
    add_blobs(hash, blobs);
    for (const BlobShape& s : detector.shapes()) {
      hash.add(s.background), hash.add(s.mxx), hash.add(s.myy), hash.add(s.mxy);
      hash.add(s.roundness);
    }
    // The windowed path: one window around each blob found.
    std::vector<blob_t> windowed;
    for (const blob_t& b : std::vector<blob_t>(blobs)) {
      detector.detect_in(image, cv::Rect(b.bbox_x - 6, b.bbox_y - 6, b.bbox_w + 12, b.bbox_h + 12),
                         90, 0, windowed);
    }
    add_blobs(hash, windowed);
  }
  EXPECT_EQ(hash.value(), 0xe2f1296eeb213dd5ull) << "blob hash 0x" << std::hex << hash.value();
}

// 640x480: a textured background, 16 noisy training frames, then frames with a person (an
// ellipse of another texture), its shadow (the background at 3/5) and, in the last, a light
// 10 % brighter everywhere.
cv::Mat background(Lcg& rng) {
  cv::Mat image(480, 640, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<uint8_t>(y, x) =
          static_cast<uint8_t>(60 + (x / 8 * 37 + y / 8 * 23) % 90 + rng.next(5));
    }
  }
  return image;
}

cv::Mat person_frame(Lcg& rng, int shift, bool brighter) {
  cv::Mat image = background(rng);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const int dx = x - 300 - shift, dy = y - 240;
      uint8_t& pixel = image.at<uint8_t>(y, x);
      if (dx * dx * 9 + dy * dy < 150 * 150) {
        pixel = static_cast<uint8_t>(170 + (x * 3 + y * 5) % 60 + rng.next(5));
      } else if (dy > 150 && dy < 220 && dx > 40 && dx < 200) {
        pixel = static_cast<uint8_t>(pixel * 3 / 5);
      }
      if (brighter) pixel = static_cast<uint8_t>(std::min(255, pixel * 11 / 10));
    }
  }
  return image;
}

TEST(VectorBits, MediPictureModelAndMasksAreTheRecordedBits) {
  Lcg rng(7);
  std::vector<cv::Mat> training;
  for (int i = 0; i < 16; ++i) training.push_back(background(rng));
  Fnv1a hash;
  for (const bool thesis : {true, false}) {
    const segmentation::MediPictureOptions options =
        thesis ? segmentation::thesis_masking_options() : segmentation::MediPictureOptions{};
    const segmentation::MediPictureModel model =
        segmentation::train_medi_picture(training, options);
    for (const cv::Mat* image :
         {&model.median, &model.sigma, &model.minimum, &model.maximum, &model.max_difference}) {
      hash.add(*image);
    }
    segmentation::MediPicture masking(model, options);
    for (int f = 0; f < 4; ++f) {
      const cv::Mat mask = masking.apply(person_frame(rng, f * 20, f == 3));
      EXPECT_GT(cv::countNonZero(mask), 10000) << "frame " << f;
      hash.add(mask);
    }
  }
  EXPECT_EQ(hash.value(), 0x874e3453059b230dull) << "mask hash 0x" << std::hex << hash.value();
}

}  // namespace
}  // namespace syncap::edge
