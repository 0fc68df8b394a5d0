// Masks as image files, the one layout every program writes them in (syncap mask, syncap
// reconstruct --mask-images and its board's masks): FOLDER/mask_NNNNNN.png, NNNNNN the frame's
// number, 255 foreground and 0 background. syncap hull and syncap calibrate --board read them.
#pragma once

#include <cstdint>
#include <filesystem>

#include <opencv2/core.hpp>

namespace syncap::segmentation {

// Writes `mask` as folder/mask_NNNNNN.png (the folder created) and returns the file. Throws
// ImageSequenceError naming the file when it cannot be written.
std::filesystem::path write_mask_image(const std::filesystem::path& folder, int64_t frame_number,
                                       const cv::Mat& mask);

}  // namespace syncap::segmentation
