// Scoring a foreground method on a CDnet 2014 folder by the benchmark's rules: only frames in
// temporalROI.txt, only pixels inside ROI.bmp; ground truth 255 is foreground, 0 and 50 (shadow)
// background, 85 (outside ROI) and 170 (unknown motion) not scored.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {

enum class SegmentationMethod { kMediPicture, kMog2, kKnn };

// "medipicture", "mog2" or "knn"; throws std::invalid_argument otherwise.
SegmentationMethod parse_segmentation_method(const std::string& name);

struct CdnetEvalOptions {
  SegmentationMethod method = SegmentationMethod::kMediPicture;
  // Medi-picture trains on the last train_frames frames before the scored range (0 = all of
  // them). MOG2 and KNN learn online from frame 1, as CDnet allows.
  int train_frames = 0;
  int frame_step = 1;  // score every frame_step-th frame of the range (all are still processed)
  MediPictureOptions medi_picture;
};

struct CdnetScores {
  int64_t true_positives = 0, false_positives = 0, false_negatives = 0, true_negatives = 0;
  int scored_frames = 0;
  double precision() const;
  double recall() const;
  double f_measure() const;
};

// Runs the method over the folder and counts. Throws std::runtime_error naming the file for a
// missing folder, file or unreadable image (with its frame number).
CdnetScores evaluate_cdnet(const std::filesystem::path& folder, const CdnetEvalOptions& options);

}  // namespace syncap::segmentation
