// JSON views of the syncap messages, and decoding an LCM payload by its type fingerprint.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "syncap/blob_frame_t.hpp"
#include "syncap/blob_t.hpp"
#include "syncap/body_frame_t.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/clip_polygon_t.hpp"
#include "syncap/edge_command_t.hpp"
#include "syncap/hull_frame_t.hpp"
#include "syncap/image_patch_t.hpp"
#include "syncap/marker_frame_t.hpp"
#include "syncap/marker_t.hpp"
#include "syncap/silhouette_part_t.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap {

// One object per message, fields in declaration order; byte arrays as base64 strings. Found by
// nlohmann::ordered_json through argument-dependent lookup, so `ordered_json j = msg;` works.
void to_json(nlohmann::ordered_json& json, const trigger_t& msg);
void to_json(nlohmann::ordered_json& json, const blob_t& msg);
void to_json(nlohmann::ordered_json& json, const blob_frame_t& msg);
void to_json(nlohmann::ordered_json& json, const silhouette_part_t& msg);
void to_json(nlohmann::ordered_json& json, const image_patch_t& msg);
void to_json(nlohmann::ordered_json& json, const camera_status_t& msg);
void to_json(nlohmann::ordered_json& json, const edge_command_t& msg);
void to_json(nlohmann::ordered_json& json, const clip_polygon_t& msg);
void to_json(nlohmann::ordered_json& json, const marker_t& msg);
void to_json(nlohmann::ordered_json& json, const marker_frame_t& msg);
void to_json(nlohmann::ordered_json& json, const hull_frame_t& msg);
void to_json(nlohmann::ordered_json& json, const body_frame_t& msg);

}  // namespace syncap

namespace syncap::io {

struct DecodedMessage {
  std::optional<std::string> type;               // "syncap.trigger_t"; nothing: unknown fingerprint
  std::optional<nlohmann::ordered_json> fields;  // nothing when the payload did not decode
  std::string error;                             // empty when the payload decoded exactly
};

// Identifies the type by the 8-byte fingerprint the payload starts with (never by channel) and
// decodes it. A payload longer than its type's encoding decodes but reports the trailing bytes.
DecodedMessage decode_message(std::span<const std::uint8_t> payload);

// Standard base64 (RFC 4648) with padding.
std::string base64_encode(std::span<const std::uint8_t> bytes);

}  // namespace syncap::io
