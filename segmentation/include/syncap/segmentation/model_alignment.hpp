// A background model learned from a separate clip of the empty scene (syncap-edge --background)
// meets a capture taken later, by a camera that may have moved: a pixel or so, from a knock, the
// tripod settling, heat. The model's edges (wall corners, lamps, door frames) then stand a pixel
// off the frame's and are called foreground all along them (a real studio's camera moved 1.04 px
// between its background clip and the capture). The shift is measured once, on the capture's
// first frame, by phase correlation (cv::phaseCorrelate: the whole image's translation, which a
// person covering a tenth of it does not move), and the model moved by it.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {

struct ModelAlignment {
  cv::Point2d shift_px;   // the frame's content relative to the model's
  double response = 0.0;  // the correlation peak's strength, 0..1
  bool applied = false;   // the model was moved (the shift large and clear enough)
  // "background clip aligned by (dx, dy) px (peak p)", or "not moved by ...": what the edge's
  // state and syncap mask say.
  std::string text() const;
};

// Shifts below this are left alone (sub-pixel noise of the measurement, and the thresholds
// already allow for the frames' own jitter)...
inline constexpr double kMinAlignedShiftPx = 0.25;
// ...and above this are no camera that settled but one that was moved: the model is left (the
// camera needs a new background clip).
inline constexpr double kMaxAlignedShiftPx = 5.0;
// A peak weaker than this is no clear translation (a frame mostly covered, a changed scene).
inline constexpr double kMinAlignmentResponse = 0.2;

// Measures the shift of `frame` (8-bit grey, the model's size) against the model's median and,
// where it is between kMinAlignedShiftPx and kMaxAlignedShiftPx with a clear peak, moves every
// image of the model by it (bilinear; the border replicated).
ModelAlignment align_model(MediPictureModel& model, const cv::Mat& frame);

}  // namespace syncap::segmentation
