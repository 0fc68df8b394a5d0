// Channel names and the datagram budget: the parts of the contract that are not in msg/*.lcm.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "syncap/proto/channels.h"

namespace syncap::proto {

// LCM (1.3/1.4 udpm) sends a message as one UDP datagram only while its 8-byte short header, the
// channel name with its NUL and the encoded message together stay under 1400 bytes; anything
// larger is fragmented, and losing any fragment loses the whole message.
inline constexpr std::size_t kLcmSingleDatagramLimit = 1400;
inline constexpr std::size_t kLcmShortHeaderSize = 8;
// Longest channel name we publish on (SYNCAP_STATUS_99 is 16 characters).
inline constexpr std::size_t kMaxChannelLength = 24;
// Every syncap message type at its documented maximum content encodes to at most this many
// bytes (1366), so it always travels as one datagram: the budget of docs/design/architecture.md.
inline constexpr std::size_t kMaxEncodedSize =
    kLcmSingleDatagramLimit - kLcmShortHeaderSize - (kMaxChannelLength + 1) - 1;

// LCM's default multicast group with ttl=0: traffic never leaves the host (or namespace).
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

// The kernel receive buffer a receiving process asks for. Every process on the group receives
// every datagram (LCM filters channels after the kernel), and the kernel charges a datagram's
// bookkeeping too: the usual 208 KiB default held 25 frames (0.8 s) of six cameras' triggers,
// blobs and silhouettes for a stopped host on the replay bench, then dropped; 4 MiB holds ~20
// times that. The kernel caps it at net.core.rmem_max, and LCM then warns on stderr (raising
// it: docs/design/edge.md, "Running syncap-edge on a board").
inline constexpr std::size_t kReceiveBufferBytes = 4u << 20;

// `url` with LCM's recv_buf_size option set to `bytes`, for a udpm URL that names none; any
// other URL (one that sets it, another provider such as file:// or memq://) is returned as is.
std::string receiving_lcm_url(std::string_view url, std::size_t bytes = kReceiveBufferBytes);

// The names, from the one table C, C++ and Python share (channels.h).
inline constexpr const char* kTriggerChannel = SYNCAP_CHANNEL_TRIGGER;
inline constexpr const char* kTriggerStatusChannel = SYNCAP_CHANNEL_TRIGGER_STATUS;
inline constexpr const char* kEdgeCommandChannel = SYNCAP_CHANNEL_EDGE_COMMAND;
inline constexpr const char* kEdgeClipChannel = SYNCAP_CHANNEL_EDGE_CLIP;
inline constexpr const char* kMarkersChannel = SYNCAP_CHANNEL_MARKERS;
inline constexpr const char* kHullChannel = SYNCAP_CHANNEL_HULL;
inline constexpr const char* kBodyChannel = SYNCAP_CHANNEL_BODY;

// Per-camera channels carry the camera id as two decimal digits: SYNCAP_BLOBS_03.
inline constexpr int kMaxCameraId = 99;
inline constexpr const char* kBlobChannelPrefix = SYNCAP_CHANNEL_BLOBS_PREFIX;
inline constexpr const char* kSilhouetteChannelPrefix = SYNCAP_CHANNEL_SILHOUETTE_PREFIX;
inline constexpr const char* kStatusChannelPrefix = SYNCAP_CHANNEL_STATUS_PREFIX;
inline constexpr const char* kPatchChannelPrefix = SYNCAP_CHANNEL_PATCH_PREFIX;

// Throws std::out_of_range for a camera id outside 0..kMaxCameraId.
std::string blob_channel(int camera_id);
std::string silhouette_channel(int camera_id);
std::string status_channel(int camera_id);
std::string patch_channel(int camera_id);

// The camera id of a per-camera channel, or nothing for any other channel name.
std::optional<int> camera_of_channel(std::string_view channel);

}  // namespace syncap::proto
