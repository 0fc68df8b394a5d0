// Every message type filled to its documented maximum content, with values that exercise the
// whole range of each field. Shared by the budget test and the on-the-wire hil test.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "syncap/blob_frame_t.hpp"
#include "syncap/body_frame_t.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/clip_polygon_t.hpp"
#include "syncap/edge_command_t.hpp"
#include "syncap/hull_frame_t.hpp"
#include "syncap/image_patch_t.hpp"
#include "syncap/marker_frame_t.hpp"
#include "syncap/silhouette_part_t.hpp"
#include "syncap/trigger_status_t.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::test {

inline trigger_t max_trigger() {
  trigger_t t{};
  t.frame_number = std::numeric_limits<int64_t>::max() - 1;
  t.monotonic_ns = 1'234'567'890'123'456'789;
  t.realtime_ns = 1'795'000'000'000'000'000;
  t.rate_hz = 1000.0;
  t.pulse_width_us = 999;
  t.trigger_id = 7;
  t.flags = trigger_t::FLAG_LATE | trigger_t::FLAG_LAST;
  return t;
}

inline blob_t blob_at(int i) {
  blob_t b{};
  b.x = 1279.5f - 0.125f * static_cast<float>(i);
  b.y = 0.0625f * static_cast<float>(i);
  b.area = 3.0f + static_cast<float>(i);
  b.peak = static_cast<int16_t>(4095 - i);
  b.bbox_x = static_cast<int16_t>(i);
  b.bbox_y = static_cast<int16_t>(2 * i);
  b.bbox_w = 12;
  b.bbox_h = 13;
  b.flags = static_cast<int8_t>(i % 16);
  return b;
}

inline blob_frame_t blob_frame_with(int blobs) {
  blob_frame_t f{};
  f.camera_id = 99;
  f.frame_number = (int64_t{1} << 40) + 17;
  f.monotonic_ns = 987'654'321'012;
  f.exposure_us = 2500;
  f.processing_us = 812;
  f.image_width = 1280;
  f.image_height = 1024;
  f.part_index = 0;
  f.part_count = 1;
  f.total_blobs = static_cast<int16_t>(blobs);
  f.num_blobs = static_cast<int16_t>(blobs);
  for (int i = 0; i < blobs; ++i) f.blobs.push_back(blob_at(i));
  return f;
}

inline blob_frame_t max_blob_frame() { return blob_frame_with(blob_frame_t::MAX_BLOBS); }

inline silhouette_part_t max_silhouette_part() {
  silhouette_part_t s{};
  s.camera_id = 99;
  s.frame_number = (int64_t{1} << 33) + 5;
  s.image_width = 1280;
  s.image_height = 1024;
  s.part_index = 3;
  s.part_count = 9;
  s.num_pieces = 12;
  s.data_size = silhouette_part_t::MAX_DATA;
  for (int i = 0; i < s.data_size; ++i) s.data.push_back(static_cast<uint8_t>(i * 37));
  return s;
}

inline image_patch_t max_image_patch() {
  image_patch_t p{};
  p.camera_id = 99;
  p.frame_number = (int64_t{1} << 33) + 5;
  p.image_width = 1280;
  p.image_height = 1024;
  p.tile_x = 1000;
  p.tile_y = 900;
  p.part_index = 40;
  p.part_count = 41;
  p.encoding = image_patch_t::ENCODING_PNG;
  p.data_size = image_patch_t::MAX_DATA;
  for (int i = 0; i < p.data_size; ++i) p.data.push_back(static_cast<uint8_t>(i * 29));
  return p;
}

inline camera_status_t max_camera_status() {
  camera_status_t s{};
  s.camera_id = 99;
  s.state = camera_status_t::STATE_ERROR;
  s.monotonic_ns = 5'000'000'000;
  s.realtime_ns = 1'795'000'000'000'000'000;
  s.last_frame_number = 123'456'789;
  s.frames_received = 123'456'000;
  s.frames_lost = 12;
  s.frames_incomplete = 3;
  s.frame_rate_hz = 29.97f;
  s.processing_us_mean = 640.5f;
  s.message = std::string(camera_status_t::MAX_MESSAGE, 'e');
  return s;
}

inline trigger_status_t max_trigger_status() {
  trigger_status_t s{};
  s.trigger_id = 7;
  s.state = trigger_status_t::STATE_ERROR;
  s.monotonic_ns = 5'000'000'000;
  s.realtime_ns = 1'795'000'000'000'000'000;
  s.pulses = 123'456'789'012;
  s.late = 1'234;
  s.missed = 56;
  s.last_frame_number = std::numeric_limits<int64_t>::max() - 1;
  s.rate_hz = 1000.0;
  s.message = std::string(trigger_status_t::MAX_MESSAGE, 't');
  return s;
}

inline edge_command_t max_edge_command() {
  edge_command_t c{};
  c.camera_id = edge_command_t::ALL_CAMERAS;
  c.sequence = 42;
  c.command = edge_command_t::SET_ROI;
  c.int_value = -1;
  c.real_value = 2500.0;
  c.roi_x = 64;
  c.roi_y = 32;
  c.roi_width = 640;
  c.roi_height = 480;
  return c;
}

inline clip_polygon_t max_clip_polygon() {
  clip_polygon_t c{};
  c.camera_id = 99;
  c.sequence = (int64_t{1} << 50) + 3;
  c.region = clip_polygon_t::REGION_SEARCH;
  c.frame_number = (int64_t{1} << 40) + 7;
  c.valid_frames = 30;
  c.image_width = 1280;
  c.image_height = 1024;
  c.num_points = clip_polygon_t::MAX_POINTS;
  for (int i = 0; i < c.num_points; ++i) {
    c.x.push_back(static_cast<int16_t>(i * 5));
    c.y.push_back(static_cast<int16_t>(1023 - i * 4));
  }
  return c;
}

inline marker_frame_t max_marker_frame() {
  marker_frame_t f{};
  f.frame_number = std::numeric_limits<int64_t>::max() - 1;
  f.trigger_monotonic_ns = 123'456'789'012'345;
  f.trigger_realtime_ns = 1'800'000'000'000'000'000;
  f.host_us = 812;
  f.flags = marker_frame_t::FLAG_COMPLETE;
  f.cameras = 8;
  f.part_count = 1;
  f.num_markers = f.total_markers = marker_frame_t::MAX_MARKERS;
  for (int i = 0; i < f.num_markers; ++i) {
    marker_t m{};
    m.id = 1'000'000 + i;
    m.x = -812.25f + static_cast<float>(i);
    m.y = 31.5f;
    m.z = 1700.125f;
    m.sigma_x = m.sigma_y = m.sigma_z = 0.25f;
    m.residual_px = 0.125f;
    m.cameras = 8;
    m.flags = marker_t::FLAG_PREDICTED;
    f.markers.push_back(m);
  }
  return f;
}

// Fixed size: every field set to a large value.
inline hull_frame_t max_hull_frame() {
  hull_frame_t h{};
  h.frame_number = std::numeric_limits<int64_t>::max() - 1;
  h.trigger_monotonic_ns = 123'456'789'012'345;
  h.trigger_realtime_ns = 1'800'000'000'000'000'000;
  h.host_us = 9'999;
  h.hull_us = 8'765;
  h.flags = hull_frame_t::FLAG_CAMERAS_MISSING | hull_frame_t::FLAG_NOT_CLOSED;
  h.cameras = 99;
  h.vertices = 2'000'000;
  h.faces = 4'000'000;
  h.volume_mm3 = 7.5e7;
  h.area_mm2 = 1.9e6;
  for (int i = 0; i < 3; ++i) {
    h.min_mm[i] = -1234.5f + static_cast<float>(i);
    h.max_mm[i] = 2345.25f - static_cast<float>(i);
  }
  return h;
}

inline body_frame_t max_body_frame() {
  body_frame_t b{};
  b.frame_number = (int64_t{1} << 41) + 9;
  b.trigger_monotonic_ns = 1'234'567'890'123;
  b.trigger_realtime_ns = 1'795'000'000'000'000'000;
  b.host_us = 2'000'000'000;
  b.fit_us = 1'999'999'999;
  b.flags = body_frame_t::FLAG_STARTED | body_frame_t::FLAG_LOST;
  b.rms_mm = 12.25f;
  b.points = 100'000;
  b.points_kept = 99'999;
  for (int i = 0; i < 60; ++i) b.parameters[i] = -3.0f + 0.1f * static_cast<float>(i);
  for (int j = 0; j < 19; ++j)
    for (int k = 0; k < 3; ++k) b.joint_mm[j][k] = 1000.5f * static_cast<float>(k) - 7.0f * j;
  b.sigma0 = 1.25f;
  for (int i = 0; i < 60; ++i) b.parameter_sigmas[i] = 0.001f * static_cast<float>(i + 1);
  for (int j = 0; j < 19; ++j) b.joint_sigma_mm[j] = 0.5f + static_cast<float>(j);
  return b;
}

}  // namespace syncap::test
