// An independent reference for the person's masks of the real 4-camera studio
// (multiview/uu-infomcv-4cam-person), not syncap's masking: each pixel's colour distance to the
// median of the camera's background clip. What the board's and syncap reconstruct's data tests
// compare with.
#pragma once

#include <algorithm>
#include <filesystem>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

namespace syncap::test {

inline constexpr int kStudioFrame = 200;  // the person seated, every view

// The person in frame `frame_number` of cam<c>/video.avi: colour distance to the median of
// background.avi above 40 (of 441), opened 5x5, the largest region.
inline cv::Mat studio_reference_mask(const std::filesystem::path& camera_dir, int frame_number) {
  cv::VideoCapture background((camera_dir / "background.avi").string());
  std::vector<cv::Mat> frames;
  for (cv::Mat f; background.read(f);) frames.push_back(f.clone());
  cv::Mat median(frames[0].size(), CV_8UC3);
  std::vector<unsigned char> values(frames.size());
  for (int y = 0; y < median.rows; ++y) {
    for (int x = 0; x < median.cols; ++x) {
      for (int ch = 0; ch < 3; ++ch) {
        for (std::size_t i = 0; i < frames.size(); ++i)
          values[i] = frames[i].at<cv::Vec3b>(y, x)[ch];
        std::ranges::nth_element(values, values.begin() + static_cast<long>(values.size() / 2));
        median.at<cv::Vec3b>(y, x)[ch] = values[values.size() / 2];
      }
    }
  }
  cv::VideoCapture video((camera_dir / "video.avi").string());
  cv::Mat frame;
  for (int i = 0; i <= frame_number; ++i) video.read(frame);
  cv::Mat difference;
  cv::absdiff(frame, median, difference);
  std::vector<cv::Mat> channels;
  cv::split(difference, channels);
  cv::Mat distance = cv::max(cv::max(channels[0], channels[1]), channels[2]);
  cv::Mat mask = distance > 40;
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::Mat::ones(5, 5, CV_8U));
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids);
  int best = 1;
  for (int i = 2; i < n; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = i;
  return labels == best;
}

}  // namespace syncap::test
