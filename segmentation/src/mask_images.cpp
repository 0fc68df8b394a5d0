#include "syncap/segmentation/mask_images.hpp"

#include <cstdio>

#include <opencv2/imgcodecs.hpp>

#include "syncap/segmentation/image_sequence.hpp"

namespace syncap::segmentation {

std::filesystem::path write_mask_image(const std::filesystem::path& folder, int64_t frame_number,
                                       const cv::Mat& mask) {
  std::filesystem::create_directories(folder);
  char name[32];
  std::snprintf(name, sizeof name, "mask_%06lld.png", static_cast<long long>(frame_number));
  const std::filesystem::path file = folder / name;
  if (!cv::imwrite(file.string(), mask)) throw ImageSequenceError("cannot write " + file.string());
  return file;
}

}  // namespace syncap::segmentation
