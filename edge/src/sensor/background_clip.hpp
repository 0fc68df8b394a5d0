// A recording of the empty scene (syncap-edge --background): the frames the medi-picture model
// trains on when the capture itself starts with the person in view (docs/design/segmentation.md,
// "Training").
#pragma once

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

namespace syncap::edge {

// Frames of a clip the model trains on unless the user says otherwise (syncap-edge and
// syncap-mask --train-frames): the model holds them all at once while it trains (50 frames of
// 1920x1200: 115 MB).
inline constexpr int kBackgroundClipFrames = 50;

// Up to `max_frames` frames of `path`, a video file or a folder of numbered images (as
// --source replay: reads them), spread evenly over the whole clip, 8-bit grey, each cropped to
// `roi` (empty: whole). Throws FrameSourceError naming the path when it cannot be read or holds
// fewer than two frames.
std::vector<cv::Mat> read_background_clip(const std::filesystem::path& path, int max_frames,
                                          const cv::Rect& roi = {});

}  // namespace syncap::edge
