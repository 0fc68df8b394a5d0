#include "syncap/segmentation/cdnet_eval.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>

namespace syncap::segmentation {
namespace {

constexpr uchar kTruthForeground = 255;
constexpr uchar kTruthShadow = 50;
constexpr uchar kTruthBackground = 0;

struct TemporalRoi {
  int first = 0, last = 0;
};

void require_exists(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error("CDnet: missing " + path.string());
  }
}

TemporalRoi read_temporal_roi(const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / "temporalROI.txt";
  require_exists(path);
  std::ifstream in(path);
  TemporalRoi roi;
  if (!(in >> roi.first >> roi.last) || roi.first < 1 || roi.last < roi.first) {
    throw std::runtime_error("CDnet: " + path.string() + " does not hold 'first last' frames");
  }
  return roi;
}

std::string numbered(const char* prefix, int frame, const char* suffix) {
  char name[64];
  std::snprintf(name, sizeof name, "%s%06d%s", prefix, frame, suffix);
  return name;
}

// A JPEG ends with its EOI marker (FF D9), which entropy-coded data never holds. OpenCV decodes a
// truncated JPEG with only a libjpeg warning on stderr, grey where the data ended; scoring it
// would count that grey silently.
bool jpeg_ends(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 1024);
  std::string bytes(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(bytes.data(), tail);
  return in && bytes.find("\xff\xd9") != std::string::npos;
}

cv::Mat read_image(const std::filesystem::path& path, int flags, int frame) {
  require_exists(path);
  const std::string extension = path.extension().string();
  if ((extension == ".jpg" || extension == ".jpeg") && !jpeg_ends(path)) {
    throw std::runtime_error("CDnet: frame " + std::to_string(frame) + " (" + path.string() +
                             ") is a truncated JPEG: no end-of-image marker");
  }
  cv::Mat image = cv::imread(path.string(), flags);
  if (image.empty()) {
    throw std::runtime_error("CDnet: cannot decode frame " + std::to_string(frame) + " (" +
                             path.string() + ")");
  }
  return image;
}

cv::Mat read_input(const std::filesystem::path& folder, int frame, int flags) {
  return read_image(folder / "input" / numbered("in", frame, ".jpg"), flags, frame);
}

// Frames are fed one at a time; each method answers with 255 where it sees foreground.
class Segmenter {
 public:
  virtual ~Segmenter() = default;
  virtual cv::Mat apply(int frame) = 0;
};

class MediPictureSegmenter : public Segmenter {
 public:
  MediPictureSegmenter(const std::filesystem::path& folder, int first_scored,
                       const CdnetEvalOptions& options)
      : folder_(folder), medi_(train(folder, first_scored, options), options.medi_picture) {}

  cv::Mat apply(int frame) override {
    return medi_.apply(read_input(folder_, frame, cv::IMREAD_GRAYSCALE));
  }

 private:
  static MediPictureModel train(const std::filesystem::path& folder, int first_scored,
                                const CdnetEvalOptions& options) {
    const int available = first_scored - 1;
    const int count =
        options.train_frames > 0 ? std::min(options.train_frames, available) : available;
    if (count < 2) {
      throw std::runtime_error("CDnet: " + folder.string() +
                               " has fewer than 2 frames before its scored range to train on");
    }
    std::vector<cv::Mat> frames;
    for (int frame = first_scored - count; frame < first_scored; ++frame) {
      frames.push_back(read_input(folder, frame, cv::IMREAD_GRAYSCALE));
    }
    return train_medi_picture(frames, options.medi_picture);
  }

  std::filesystem::path folder_;
  MediPicture medi_;
};

// OpenCV's MOG2 or KNN with default parameters and shadow detection; a shadow (127) counts as
// background, as CDnet scores it.
class OpenCvSegmenter : public Segmenter {
 public:
  OpenCvSegmenter(const std::filesystem::path& folder, cv::Ptr<cv::BackgroundSubtractor> method)
      : folder_(folder), method_(std::move(method)) {}

  cv::Mat apply(int frame) override {
    cv::Mat mask;
    method_->apply(read_input(folder_, frame, cv::IMREAD_COLOR), mask);
    return mask == 255;
  }

 private:
  std::filesystem::path folder_;
  cv::Ptr<cv::BackgroundSubtractor> method_;
};

void count_frame(const cv::Mat& mask, const cv::Mat& truth, const cv::Mat& roi,
                 CdnetScores& scores) {
  for (int y = 0; y < mask.rows; ++y) {
    const uchar* m = mask.ptr<uchar>(y);
    const uchar* t = truth.ptr<uchar>(y);
    const uchar* r = roi.ptr<uchar>(y);
    for (int x = 0; x < mask.cols; ++x) {
      if (r[x] == 0) continue;
      const bool detected = m[x] != 0;
      if (t[x] == kTruthForeground) {
        ++(detected ? scores.true_positives : scores.false_negatives);
      } else if (t[x] == kTruthBackground || t[x] == kTruthShadow) {
        ++(detected ? scores.false_positives : scores.true_negatives);
      }
    }
  }
  ++scores.scored_frames;
}

double ratio(int64_t numerator, int64_t denominator) {
  return denominator > 0 ? static_cast<double>(numerator) / static_cast<double>(denominator) : 0.0;
}

}  // namespace

SegmentationMethod parse_segmentation_method(const std::string& name) {
  if (name == "medipicture") return SegmentationMethod::kMediPicture;
  if (name == "mog2") return SegmentationMethod::kMog2;
  if (name == "knn") return SegmentationMethod::kKnn;
  throw std::invalid_argument("unknown method '" + name + "' (medipicture, mog2 or knn)");
}

double CdnetScores::precision() const {
  return ratio(true_positives, true_positives + false_positives);
}

double CdnetScores::recall() const {
  return ratio(true_positives, true_positives + false_negatives);
}

double CdnetScores::f_measure() const {
  const double p = precision(), r = recall();
  return p + r > 0 ? 2 * p * r / (p + r) : 0.0;
}

CdnetScores evaluate_cdnet(const std::filesystem::path& folder, const CdnetEvalOptions& options) {
  if (!std::filesystem::is_directory(folder)) {
    throw std::runtime_error("CDnet: no folder " + folder.string());
  }
  const TemporalRoi scored = read_temporal_roi(folder);
  cv::Mat roi = read_image(folder / "ROI.bmp", cv::IMREAD_GRAYSCALE, 0);

  std::unique_ptr<Segmenter> segmenter;
  int first_processed = 1;
  switch (options.method) {
    case SegmentationMethod::kMediPicture:
      segmenter = std::make_unique<MediPictureSegmenter>(folder, scored.first, options);
      first_processed = scored.first;
      break;
    case SegmentationMethod::kMog2:
      segmenter = std::make_unique<OpenCvSegmenter>(folder, cv::createBackgroundSubtractorMOG2());
      break;
    case SegmentationMethod::kKnn:
      segmenter = std::make_unique<OpenCvSegmenter>(folder, cv::createBackgroundSubtractorKNN());
      break;
  }

  const int step = std::max(1, options.frame_step);
  CdnetScores scores;
  for (int frame = first_processed; frame <= scored.last; ++frame) {
    const cv::Mat mask = segmenter->apply(frame);
    if (frame < scored.first || (frame - scored.first) % step != 0) continue;
    const cv::Mat truth = read_image(folder / "groundtruth" / numbered("gt", frame, ".png"),
                                     cv::IMREAD_GRAYSCALE, frame);
    if (truth.size() != mask.size() || roi.size() != mask.size()) {
      throw std::runtime_error("CDnet: frame " + std::to_string(frame) +
                               ": input, ground truth and ROI.bmp differ in size");
    }
    count_frame(mask, truth, roi, scores);
  }
  return scores;
}

}  // namespace syncap::segmentation
