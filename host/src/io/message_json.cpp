#include "io/message_json.hpp"

#include <array>
#include <iomanip>
#include <sstream>

#include "syncap/proto/decode.hpp"
// Declared here rather than in message_json.hpp: the log decodes it by fingerprint below.
#include "syncap/trigger_status_t.hpp"

namespace syncap {

void to_json(nlohmann::ordered_json& json, const trigger_t& msg) {
  json = {
      {"frame_number", msg.frame_number},
      {"monotonic_ns", msg.monotonic_ns},
      {"realtime_ns", msg.realtime_ns},
      {"rate_hz", msg.rate_hz},
      {"pulse_width_us", msg.pulse_width_us},
      {"trigger_id", msg.trigger_id},
      {"flags", msg.flags},
  };
}

void to_json(nlohmann::ordered_json& json, const blob_t& msg) {
  json = {
      {"x", msg.x},           {"y", msg.y},           {"area", msg.area},
      {"peak", msg.peak},     {"bbox_x", msg.bbox_x}, {"bbox_y", msg.bbox_y},
      {"bbox_w", msg.bbox_w}, {"bbox_h", msg.bbox_h}, {"flags", msg.flags},
  };
}

void to_json(nlohmann::ordered_json& json, const blob_frame_t& msg) {
  json = {
      {"camera_id", msg.camera_id},         {"frame_number", msg.frame_number},
      {"monotonic_ns", msg.monotonic_ns},   {"exposure_us", msg.exposure_us},
      {"processing_us", msg.processing_us}, {"image_width", msg.image_width},
      {"image_height", msg.image_height},   {"part_index", msg.part_index},
      {"part_count", msg.part_count},       {"total_blobs", msg.total_blobs},
      {"num_blobs", msg.num_blobs},         {"blobs", msg.blobs},
  };
}

void to_json(nlohmann::ordered_json& json, const silhouette_part_t& msg) {
  json = {
      {"camera_id", msg.camera_id},          {"frame_number", msg.frame_number},
      {"image_width", msg.image_width},      {"image_height", msg.image_height},
      {"part_index", msg.part_index},        {"part_count", msg.part_count},
      {"num_pieces", msg.num_pieces},        {"data_size", msg.data_size},
      {"data", io::base64_encode(msg.data)},
  };
}

void to_json(nlohmann::ordered_json& json, const image_patch_t& msg) {
  json = {
      {"camera_id", msg.camera_id},
      {"frame_number", msg.frame_number},
      {"image_width", msg.image_width},
      {"image_height", msg.image_height},
      {"tile_x", msg.tile_x},
      {"tile_y", msg.tile_y},
      {"part_index", msg.part_index},
      {"part_count", msg.part_count},
      {"encoding", msg.encoding},
      {"data_size", msg.data_size},
      {"data", io::base64_encode(msg.data)},
  };
}

void to_json(nlohmann::ordered_json& json, const camera_status_t& msg) {
  json = {
      {"camera_id", msg.camera_id},
      {"state", msg.state},
      {"monotonic_ns", msg.monotonic_ns},
      {"realtime_ns", msg.realtime_ns},
      {"last_frame_number", msg.last_frame_number},
      {"frames_received", msg.frames_received},
      {"frames_lost", msg.frames_lost},
      {"frames_incomplete", msg.frames_incomplete},
      {"frame_rate_hz", msg.frame_rate_hz},
      {"processing_us_mean", msg.processing_us_mean},
      {"commands_accepted", msg.commands_accepted},
      {"commands_rejected", msg.commands_rejected},
      {"last_command_sender", msg.last_command_sender},
      {"last_command_sequence", msg.last_command_sequence},
      {"last_command_result", msg.last_command_result},
      {"message", msg.message},
  };
}

void to_json(nlohmann::ordered_json& json, const marker_t& msg) {
  json = {
      {"id", msg.id},
      {"x", msg.x},
      {"y", msg.y},
      {"z", msg.z},
      {"sigma_x", msg.sigma_x},
      {"sigma_y", msg.sigma_y},
      {"sigma_z", msg.sigma_z},
      {"residual_px", msg.residual_px},
      {"cameras", msg.cameras},
      {"flags", msg.flags},
  };
}

void to_json(nlohmann::ordered_json& json, const marker_frame_t& msg) {
  json = {
      {"frame_number", msg.frame_number},
      {"trigger_monotonic_ns", msg.trigger_monotonic_ns},
      {"trigger_realtime_ns", msg.trigger_realtime_ns},
      {"host_us", msg.host_us},
      {"flags", msg.flags},
      {"cameras", msg.cameras},
      {"part_index", msg.part_index},
      {"part_count", msg.part_count},
      {"total_markers", msg.total_markers},
      {"num_markers", msg.num_markers},
      {"markers", msg.markers},
  };
}

void to_json(nlohmann::ordered_json& json, const hull_frame_t& msg) {
  json = {
      {"frame_number", msg.frame_number},
      {"trigger_monotonic_ns", msg.trigger_monotonic_ns},
      {"trigger_realtime_ns", msg.trigger_realtime_ns},
      {"host_us", msg.host_us},
      {"hull_us", msg.hull_us},
      {"flags", msg.flags},
      {"cameras", msg.cameras},
      {"vertices", msg.vertices},
      {"faces", msg.faces},
      {"volume_mm3", msg.volume_mm3},
      {"area_mm2", msg.area_mm2},
      {"min_mm", msg.min_mm},
      {"max_mm", msg.max_mm},
  };
}

void to_json(nlohmann::ordered_json& json, const body_frame_t& msg) {
  nlohmann::ordered_json joints = nlohmann::ordered_json::array();
  for (const auto& joint : msg.joint_mm) joints.push_back(joint);
  json = {
      {"frame_number", msg.frame_number},
      {"trigger_monotonic_ns", msg.trigger_monotonic_ns},
      {"trigger_realtime_ns", msg.trigger_realtime_ns},
      {"host_us", msg.host_us},
      {"fit_us", msg.fit_us},
      {"flags", msg.flags},
      {"rms_mm", msg.rms_mm},
      {"points", msg.points},
      {"points_kept", msg.points_kept},
      {"parameters", msg.parameters},
      {"joint_mm", joints},
      {"sigma0", msg.sigma0},
      {"parameter_sigmas", msg.parameter_sigmas},
      {"joint_sigma_mm", msg.joint_sigma_mm},
  };
}

// The trigger module's heartbeat (proto/msg/trigger_status_t.lcm).
void to_json(nlohmann::ordered_json& json, const trigger_status_t& msg);
void to_json(nlohmann::ordered_json& json, const trigger_status_t& msg) {
  json = {
      {"trigger_id", msg.trigger_id},
      {"state", msg.state},
      {"monotonic_ns", msg.monotonic_ns},
      {"realtime_ns", msg.realtime_ns},
      {"pulses", msg.pulses},
      {"late", msg.late},
      {"missed", msg.missed},
      {"last_frame_number", msg.last_frame_number},
      {"rate_hz", msg.rate_hz},
      {"message", msg.message},
  };
}

namespace {

// A command's MAC as 64 hexadecimal digits.
std::string mac_hex(const int8_t (&mac)[32]) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex;
  for (const int8_t byte : mac) {
    const auto b = static_cast<uint8_t>(byte);
    hex += kDigits[b >> 4];
    hex += kDigits[b & 15];
  }
  return hex;
}

}  // namespace

void to_json(nlohmann::ordered_json& json, const edge_command_t& msg) {
  json = {
      {"camera_id", msg.camera_id},   {"sender", msg.sender},
      {"sequence", msg.sequence},     {"sent_realtime_ns", msg.sent_realtime_ns},
      {"command", msg.command},       {"int_value", msg.int_value},
      {"real_value", msg.real_value}, {"roi_x", msg.roi_x},
      {"roi_y", msg.roi_y},           {"roi_width", msg.roi_width},
      {"roi_height", msg.roi_height}, {"mac", mac_hex(msg.mac)},
  };
}

void to_json(nlohmann::ordered_json& json, const clip_polygon_t& msg) {
  json = {
      {"camera_id", msg.camera_id},
      {"sender", msg.sender},
      {"sequence", msg.sequence},
      {"sent_realtime_ns", msg.sent_realtime_ns},
      {"region", msg.region == clip_polygon_t::REGION_FLOOR    ? "floor"
                 : msg.region == clip_polygon_t::REGION_SEARCH ? "search"
                 : msg.region == clip_polygon_t::REGION_CLIP   ? "clip"
                                                               : "unknown"},
      {"frame_number", msg.frame_number},
      {"valid_frames", msg.valid_frames},
      {"image_width", msg.image_width},
      {"image_height", msg.image_height},
      {"num_points", msg.num_points},
      {"x", msg.x},
      {"y", msg.y},
      {"mac", mac_hex(msg.mac)},
  };
}

}  // namespace syncap

namespace syncap::io {
namespace {

constexpr std::size_t kFingerprintSize = 8;

template <class Message>
DecodedMessage decode_as(std::span<const std::uint8_t> payload) {
  DecodedMessage decoded;
  decoded.type = std::string("syncap.") + Message::getTypeName();
  Message msg;
  const int size = static_cast<int>(payload.size());
  const proto::DecodeResult result = proto::try_decode(payload.data(), payload.size(), msg);
  const int used = result.used;
  if (!result.ok()) {
    decoded.error = "payload of " + std::to_string(size) + " bytes does not decode as " +
                    *decoded.type + ": " + result.error;
    return decoded;
  }
  decoded.fields = nlohmann::ordered_json(msg);
  if (used != size) {
    decoded.error = *decoded.type + " decoded from " + std::to_string(used) + " of " +
                    std::to_string(size) + " payload bytes; the rest is trailing garbage";
  }
  return decoded;
}

struct KnownType {
  std::int64_t fingerprint;
  DecodedMessage (*decode)(std::span<const std::uint8_t>);
};

template <class Message>
KnownType known() {
  return {Message::getHash(), &decode_as<Message>};
}

const std::array<KnownType, 13>& known_types() {
  static const std::array<KnownType, 13> types{
      known<trigger_t>(),         known<blob_t>(),          known<blob_frame_t>(),
      known<silhouette_part_t>(), known<camera_status_t>(), known<edge_command_t>(),
      known<trigger_status_t>(),  known<clip_polygon_t>(),  known<marker_t>(),
      known<marker_frame_t>(),    known<hull_frame_t>(),    known<body_frame_t>(),
      known<image_patch_t>()};
  return types;
}

std::int64_t read_fingerprint(std::span<const std::uint8_t> payload) {
  std::uint64_t value = 0;
  for (const std::uint8_t byte : payload.first(kFingerprintSize)) value = (value << 8) | byte;
  return static_cast<std::int64_t>(value);
}

std::string hex64(std::int64_t value) {
  std::ostringstream text;
  text << "0x" << std::hex << std::setw(16) << std::setfill('0')
       << static_cast<std::uint64_t>(value);
  return text.str();
}

DecodedMessage undecoded(std::string error) {
  DecodedMessage decoded;
  decoded.error = std::move(error);
  return decoded;
}

}  // namespace

DecodedMessage decode_message(std::span<const std::uint8_t> payload) {
  if (payload.size() < kFingerprintSize) {
    return undecoded("payload of " + std::to_string(payload.size()) +
                     " bytes is too short for a type fingerprint");
  }
  const std::int64_t fingerprint = read_fingerprint(payload);
  for (const KnownType& type : known_types()) {
    if (type.fingerprint == fingerprint) return type.decode(payload);
  }
  return undecoded("unknown type fingerprint " + hex64(fingerprint));
}

std::string base64_encode(std::span<const std::uint8_t> bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t count = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 3; ++k) group = (group << 8) | (k < count ? bytes[i + k] : 0u);
    for (std::size_t k = 0; k < 4; ++k) {
      text += k <= count ? kAlphabet[(group >> (18 - 6 * k)) & 0x3f] : '=';
    }
  }
  return text;
}

}  // namespace syncap::io
