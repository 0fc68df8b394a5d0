// A recording of the synthetic person for the tests of syncap reconstruct and its controller:
// per camera an image folder of the empty room (a fixed texture with sensor noise) and one of
// the person standing in it, brighter than the room (no shadow), the person drawn through the
// camera model (tests/host/hull/hull_scenes.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "hull/hull_scenes.hpp"

namespace syncap::test {

struct RecordingFolders {
  std::filesystem::path capture, background;  // of one camera
};

struct PersonRecording {
  int first_frame = 10, frames = 3;  // the capture's frame numbers
  int background_frames = 8;
  // A false region in one camera's capture (a chair moved in): a bright box there.
  std::optional<int> camera_with_chair;
};

// `image` with 2 DN of sensor noise as `folder`/frame_k.png.
inline void write_noisy(const cv::Mat& image, const std::filesystem::path& folder, int k,
                        cv::RNG& rng) {
  std::filesystem::create_directories(folder);
  cv::Mat noise(image.size(), CV_16SC1);
  rng.fill(noise, cv::RNG::NORMAL, 0, 2);
  cv::Mat noisy;
  cv::add(image, noise, noisy, cv::noArray(), CV_8U);
  cv::imwrite((folder / ("frame_" + std::to_string(k) + ".png")).string(), noisy);
}

// Writes dir/background/camN and dir/capture/camN for every camera; their folders in camera order.
inline std::vector<RecordingFolders> write_person_recording(
    const std::filesystem::path& dir, const std::vector<sensor::CameraModel>& cameras,
    const PersonRecording& what = {}) {
  const hull::Mesh person = hull::test::person_mesh();
  cv::RNG rng(11);
  std::vector<RecordingFolders> folders;
  for (const sensor::CameraModel& camera : cameras) {
    cv::Mat room(camera.sensor.height_px, camera.sensor.width_px, CV_8UC1);
    rng.fill(room, cv::RNG::UNIFORM, 60, 140);
    const std::string cam = "cam" + std::to_string(camera.id);
    RecordingFolders f{dir / "capture" / cam, dir / "background" / cam};
    for (int k = 0; k < what.background_frames; ++k) write_noisy(room, f.background, k, rng);
    cv::Mat frame = room.clone();
    frame.setTo(220, hull::render_mask(person, camera));
    if (what.camera_with_chair == camera.id) frame(cv::Rect(20, 360, 50, 60)).setTo(230);
    for (int k = what.first_frame; k < what.first_frame + what.frames; ++k)
      write_noisy(frame, f.capture, k, rng);
    folders.push_back(f);
  }
  return folders;
}

}  // namespace syncap::test
