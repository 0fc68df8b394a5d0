/* The LCM channel names: the one table C (the trigger), C++ (syncap/proto/channels.hpp) and
 * Python (host/viewer/syncap_view/channels.py, which reads this file) take them from. One
 * `#define SYNCAP_CHANNEL_<NAME> "<channel>"` a line: the Python reader expects that form.
 * Per-camera channels are a prefix and the camera id in two decimal digits (SYNCAP_BLOBS_03). */
#ifndef SYNCAP_PROTO_CHANNELS_H
#define SYNCAP_PROTO_CHANNELS_H

/* trigger_t, the trigger's pulses with their frame numbers (docs/trigger.md). */
#define SYNCAP_CHANNEL_TRIGGER "SYNCAP_TRIGGER"
/* trigger_status_t, the trigger's heartbeat. */
#define SYNCAP_CHANNEL_TRIGGER_STATUS "SYNCAP_TRIGGER_STATUS"
/* edge_command_t, host -> edges (signed: docs/security.md). */
#define SYNCAP_CHANNEL_EDGE_COMMAND "SYNCAP_EDGE_CMD"
/* clip_polygon_t, host -> edge (each message names its camera). */
#define SYNCAP_CHANNEL_EDGE_CLIP "SYNCAP_EDGE_CLIP"
/* marker_frame_t: the host's 3D markers of each frame. */
#define SYNCAP_CHANNEL_MARKERS "SYNCAP_MARKERS"
/* hull_frame_t: the measures of the host's visual hull of each frame. */
#define SYNCAP_CHANNEL_HULL "SYNCAP_HULL"
/* body_frame_t: the body fitted to each frame's visual hull. */
#define SYNCAP_CHANNEL_BODY "SYNCAP_BODY"

/* Per-camera prefixes. */
#define SYNCAP_CHANNEL_BLOBS_PREFIX "SYNCAP_BLOBS_"
#define SYNCAP_CHANNEL_SILHOUETTE_PREFIX "SYNCAP_SIL_"
#define SYNCAP_CHANNEL_STATUS_PREFIX "SYNCAP_STATUS_"
/* image_patch_t: grey values where the person is, every Nth frame on request. */
#define SYNCAP_CHANNEL_PATCH_PREFIX "SYNCAP_PATCH_"

#endif
