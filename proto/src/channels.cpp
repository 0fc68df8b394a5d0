#include "syncap/proto/channels.hpp"

#include <charconv>
#include <stdexcept>

namespace syncap::proto {
namespace {

std::string per_camera_channel(const char* prefix, int camera_id) {
  if (camera_id < 0 || camera_id > kMaxCameraId) {
    throw std::out_of_range("camera id " + std::to_string(camera_id) + " outside 0.." +
                            std::to_string(kMaxCameraId));
  }
  std::string name(prefix);
  if (camera_id < 10) name += '0';
  name += std::to_string(camera_id);
  return name;
}

}  // namespace

std::string blob_channel(int camera_id) {
  return per_camera_channel(kBlobChannelPrefix, camera_id);
}

std::string silhouette_channel(int camera_id) {
  return per_camera_channel(kSilhouetteChannelPrefix, camera_id);
}

std::string patch_channel(int camera_id) {
  return per_camera_channel(kPatchChannelPrefix, camera_id);
}

std::string status_channel(int camera_id) {
  return per_camera_channel(kStatusChannelPrefix, camera_id);
}

std::optional<int> camera_of_channel(std::string_view channel) {
  for (std::string_view prefix :
       {kBlobChannelPrefix, kSilhouetteChannelPrefix, kStatusChannelPrefix, kPatchChannelPrefix}) {
    if (!channel.starts_with(prefix)) continue;
    std::string_view digits = channel.substr(prefix.size());
    if (digits.size() != 2) return std::nullopt;
    int id = 0;
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), id);
    if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
    return id;
  }
  return std::nullopt;
}

std::string receiving_lcm_url(std::string_view url, std::size_t bytes) {
  std::string out(url);
  if (!url.starts_with("udpm://") || url.find("recv_buf_size=") != std::string_view::npos) {
    return out;
  }
  out += url.find('?') == std::string_view::npos ? '?' : '&';
  return out + "recv_buf_size=" + std::to_string(bytes);
}

}  // namespace syncap::proto
