// A recording of the empty scene (syncap-edge --background, syncap mask, syncap reconstruct): the
// frames the medi-picture model trains on when the capture itself starts with the person in view
// (docs/design/segmentation.md, "Training").
#pragma once

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

namespace syncap::segmentation {

// Frames of a clip the model trains on unless the user says otherwise (--train-frames): the model
// holds them all at once while it trains (50 frames of 1920x1200: 115 MB).
inline constexpr int kBackgroundClipFrames = 50;

// Up to `max_frames` frames of `path`, a video file or a folder of numbered images
// (open_image_sequence), spread evenly over the whole clip, 8-bit grey, each cropped to `roi`
// (empty: whole). Throws ImageSequenceError naming the path when it cannot be read, when `roi`
// lies outside its images, or when it holds fewer than two frames.
std::vector<cv::Mat> read_background_clip(const std::filesystem::path& path, int max_frames,
                                          const cv::Rect& roi = {});

}  // namespace syncap::segmentation
