// Medi-picture foreground masking (thesis 5.1.2, eqs 5.5-5.11): a per-pixel model of the empty
// scene learnt from N training frames, a frame classified against it, darker pixels whose
// neighbourhood correlates with the background's taken back as shadow, then closing, removal of
// small components and an optional clip polygon. Grey images (CV_8UC1) throughout.
#pragma once

#include <span>
#include <vector>

#include <opencv2/core.hpp>

#include <memory>

#include "syncap/segmentation/packed_mask.hpp"
#include "syncap/segmentation/radiometric_lsm.hpp"

namespace syncap::segmentation {

// The empty scene as eq 5.5 describes it, each image the size of the training frames.
struct MediPictureModel {
  cv::Mat median;          // lambda, CV_32FC1: also the background image B of the NCC test
  cv::Mat sigma;           // sigma, CV_32FC1: 1.4826 x median absolute deviation from lambda
  cv::Mat minimum;         // m, CV_32FC1: minimum over the stationary frames
  cv::Mat maximum;         // n, CV_32FC1: maximum over the stationary frames
  cv::Mat max_difference;  // d, CV_32FC1: largest step between consecutive stationary frames
};

// Learns the model from frames of the empty scene (at least 2, all CV_8UC1 of one size). A frame
// z counts as stationary at a pixel when |S_z - lambda| <= 2 sigma there; d takes only steps
// between two consecutive stationary frames. Throws std::invalid_argument on bad input.
MediPictureModel train_medi_picture(std::span<const cv::Mat> frames);

// How darker foreground pixels are recognised as shadow.
enum class ShadowTest {
  // Eqs 5.6-5.11: the window around the pixel correlates with the background's (NCC >= L_NCC)
  // and holds less energy.
  kCorrelation,
  // Our alternative for scenes with one light: every shadow pixel is the background darkened by
  // the same factor. The factor is the mode of I / lambda over the candidates of the frame; a
  // candidate is shadow when |I - factor lambda| <= shadow_ratio_sigmas x max(sigma, 1 DN).
  // Per pixel, so it has no border band where the window straddles the shadow's edge, and a
  // smooth dark body part is kept unless its darkening happens to equal the shadow's.
  kCommonRatio,
};

// The defaults are the one setting measured best on both a real scene (CDnet highway) and the
// replay bench's person (docs/design/segmentation.md "The default"): a narrow interval (k 1.5), the
// common-ratio shadow test at 3 sigmas, a closing of 5 px, holes up to 100 px filled and each
// frame's illumination corrected by least-squares matching. thesis_masking_options() gives the
// parameters the thesis' text suggests, for comparison.
struct MediPictureOptions {
  // A pixel is foreground outside [m - k d', n + k d'] with d' = max(d, min_difference).
  float k = 1.5f;
  float min_difference = 6.0f;  // DN: d of a pixel still in training is not its noise
  // Shadow test on the pixels darker than the interval.
  bool remove_shadows = true;
  ShadowTest shadow_test = ShadowTest::kCommonRatio;
  float shadow_ratio_sigmas = 3.0f;  // kCommonRatio: tolerance in the pixel's training sigmas
  // kCommonRatio: a darkening factor below this is not a shadow (a room's ambient light keeps a
  // shadow above ~0.4 of the lit floor) but a dark object of the frame, which alone makes the
  // mode when there is no shadow; with a low factor the tolerance of a few DN spans a wide range
  // of floor brightness and would take much of the object for shadow.
  float min_shadow_ratio = 0.3f;
  int ncc_half_window = 2;      // kCorrelation: N of the (2N + 1)^2 window
  float ncc_threshold = 0.98f;  // kCorrelation: L_NCC
  // kCorrelation, our addition: a shadow keeps at least this share of the background's energy
  // (E_T / E_B); without it a uniform dark object on a uniform floor passes eqs 5.10/5.11.
  float min_shadow_energy_ratio = 0.5f;
  int closing_diameter = 5;     // elliptical element, pixels; 0 disables the closing
  int min_component_area = 40;  // smaller 8-connected components are noise, pixels
  // Holes of the foreground (4-connected background not reaching the image border) up to this
  // area are filled, pixels; 0 keeps every hole. A person's silhouette has few true holes that
  // small; pixels of the body that match the background leave many.
  int max_hole_area = 100;
  float update_rate = 0.0f;  // slow update where the mask is background, 0 = frozen model
  // Least-squares matching (eqs 5.12-5.20, radiometric_lsm.hpp) of each frame against the
  // background before classification: the frame is brought to the training's illumination
  // (gain and offset per window of a grid), so lamps drifting or flickering do not fill the mask.
  // Training frames are then normalised too (train_medi_picture with these options).
  bool correct_illumination = true;
  RadiometricOptions illumination;
  std::vector<cv::Point> clip_polygon;  // when not empty, pixels outside it are background
  // When not empty, only pixels inside can be shadow (thesis 5.1.3: the ground plane; the host
  // sends the floor's polygon): a dark part of the person against a wall stays foreground.
  std::vector<cv::Point> floor_polygon;
  // When not empty, only pixels inside are classified (the tracked body's projection, thesis
  // Fig 5.8); the rest is background, and the classification visits only its bounding box.
  std::vector<cv::Point> search_polygon;
  // With a search region, every this many frames the whole frame is classified all the same, to
  // find the shadow's factor (kCommonRatio) where the region holds too little of the shadow.
  int search_refresh_frames = 10;
  // A silhouette with more than this many pixels on the search region's rim was cut by the
  // region: the frames after it are classified whole until a new region is set
  // (MediPicture::regions_cut counts them).
  int search_cut_pixels = 10;
};

// The parameters of the thesis' text (k 3, the correlation shadow test of eqs 5.6-5.11 with
// L_NCC 0.98, a closing of 9 px, no hole filling, no illumination correction).
MediPictureOptions thesis_masking_options();

// The same after bringing the frames to one illumination (normalise_training_frames) when
// options.correct_illumination is set.
MediPictureModel train_medi_picture(std::span<const cv::Mat> frames,
                                    const MediPictureOptions& options);

// Classifies frames against a trained model; holds the thresholds derived from it.
class MediPicture {
 public:
  // Keeps its own copy of the model's images.
  MediPicture(const MediPictureModel& model, MediPictureOptions options);

  // The foreground mask of `frame` (CV_8UC1, the model's size): 255 foreground, 0 background.
  // With update_rate > 0 the model then follows the scene where the mask is background.
  // One pass classifies every pixel; the shadow test, closing and component filter then run
  // only inside the bounding boxes of what that pass found. The result is the same as that of
  // the free functions below applied in turn (tested). The returned image is reused by the next
  // call when the caller no longer holds it.
  cv::Mat apply(const cv::Mat& frame);

  // Replaces the clip polygon (pixels of the model's image; empty: no clip).
  void set_clip_polygon(std::vector<cv::Point> polygon);
  // Replaces the floor polygon (MediPictureOptions::floor_polygon; empty: all is floor).
  void set_floor_polygon(std::vector<cv::Point> polygon);
  // Replaces the search region (MediPictureOptions::search_polygon; empty: the whole frame).
  void set_search_region(std::vector<cv::Point> polygon);

  const MediPictureModel& model() const { return model_; }
  const MediPictureOptions& options() const { return options_; }
  // Frames whose silhouette the search region cut (each followed by a whole frame).
  long regions_cut() const { return regions_cut_; }
  // The last frame was classified in the search region only.
  bool searched() const { return restricted_; }
  // The illumination correction of the last frame; nullptr when correct_illumination is off.
  const RadiometricCorrection* illumination() const { return illumination_.get(); }

 private:
  void derive_thresholds();
  void combine_regions();
  void decide_search();
  // Where this frame's pixels may be foreground: clip and search region when restricted_, the
  // clip alone on a whole frame.
  const cv::Mat& frame_allowed() const { return restricted_ ? allowed_ : clip_; }
  void update_model(const cv::Mat& frame, const cv::Mat& mask);
  // The steps one after the other over the whole frame (the free functions); used when the
  // options rule out the fast path.
  cv::Mat apply_whole_frame(const cv::Mat& frame);
  // Eqs 5.6-5.11 on the pixels marked kBelow in `mask` within `box`: 0 if shadow, else 255.
  void resolve_shadows(const cv::Mat& frame, cv::Mat& mask, cv::Rect box);
  // The common-ratio test on the pixels marked kBelow in `mask` within `box`: 0 if shadow, else
  // 255.
  void resolve_common_ratio_shadows(const cv::Mat& frame, cv::Mat& mask, cv::Rect box);
  // clean_mask and the clip inside `box`, which holds every foreground pixel of `mask`.
  void clean_inside(cv::Mat& mask, cv::Rect box);

  MediPictureModel model_;
  MediPictureOptions options_;
  cv::Mat lower_, upper_;      // CV_8UC1 bounds of the background interval
  cv::Mat background_;         // CV_8UC1 median, the B of the NCC test
  cv::Mat background_energy_;  // CV_32FC1 window sums of B^2
  cv::Mat clip_;               // CV_8UC1 255 inside the clip polygon, empty when none
  cv::Mat floor_;              // CV_8UC1 255 inside the floor polygon, empty when none
  cv::Mat search_;             // CV_8UC1 255 inside the search region, empty when none
  cv::Mat allowed_;            // clip_ and search_ combined, empty when neither
  cv::Rect search_box_;        // the search region's bounding box, or the whole image
  // The search region's state between frames (apply's comment).
  bool restricted_ = false;        // this frame is classified in the search region only
  float remembered_ratio_ = 0.0f;  // the shadow's factor from the last whole frame
  int frames_since_refresh_ = 0;
  cv::Mat search_border_;    // the search region's inner rim, 2 px
  bool region_cut_ = false;  // the last frame's silhouette reached the rim
  long regions_cut_ = 0;
  // lower <= background <= upper everywhere: then the candidates of the shadow test are exactly
  // the pixels below the interval. False (odd options) selects apply_whole_frame.
  bool fast_path_ = false;
  // Buffers kept between frames.
  cv::Mat mask_;                                  // the last mask returned
  std::vector<uchar> row_below_, row_any_;        // per row: any pixel below / outside
  std::vector<uchar> column_below_, column_any_;  // per stripe and column: the same
  std::vector<int> window_columns_;               // reflected column of each window column
  std::vector<int> sum_cross_, sum_frame_;        // per column: window sums of I.B and I^2
  std::vector<int> window_cross_, window_frame_;  // per pixel of a row: the same, whole window
  cv::Mat work_, labels_, stats_, centroids_;     // clean_inside
  detail::PackedMask packed_;                     // clean_inside
  std::unique_ptr<RadiometricCorrection> illumination_;
};

// The steps of MediPicture::apply, each usable on its own.

// 255 where `frame` lies outside the model's interval [m - k d', n + k d'].
cv::Mat classify_against_model(const MediPictureModel& model, const cv::Mat& frame,
                               const MediPictureOptions& options);

// 255 where a pixel of `candidates` is shadow by eqs 5.10/5.11 (and the energy ratio bound):
// the window of `frame` correlates with that of `background` and holds less energy.
cv::Mat shadow_pixels(const cv::Mat& background, const cv::Mat& frame, const cv::Mat& candidates,
                      const MediPictureOptions& options);

// kCommonRatio: the darkening factor of the frame's shadow, the mode of frame / lambda over the
// pixels of `candidates` (bins of 0.01 below 1, smoothed over three); 0 when there is none.
float shadow_ratio(const MediPictureModel& model, const cv::Mat& frame, const cv::Mat& candidates);

// kCommonRatio: 255 where a pixel of `candidates` is the background darkened by `ratio` within
// options.shadow_ratio_sigmas x max(sigma, 1); none when ratio < options.min_shadow_ratio.
cv::Mat common_ratio_shadow_pixels(const MediPictureModel& model, const cv::Mat& frame,
                                   const cv::Mat& candidates, float ratio,
                                   const MediPictureOptions& options);

// Fills the holes of `mask` (4-connected background components that do not touch the image
// border) of at most `max_area` pixels. Works in place.
void fill_holes(cv::Mat& mask, int max_area);

// Closing with an elliptical element of `closing_diameter`, then removal of 8-connected
// components smaller than `min_component_area`. Works in place.
void clean_mask(cv::Mat& mask, int closing_diameter, int min_component_area);

// Sets the pixels of `mask` outside `polygon` to background (nothing when it is empty).
void clip_to_polygon(cv::Mat& mask, std::span<const cv::Point> polygon);

// Keeps the largest 8-connected foreground region of `mask` (ties: the first in scan order),
// removing every other: one person's silhouette against the room's false regions (lamps, edges,
// moved furniture), which a person seen whole is never split from. Works in place.
void keep_largest_region(cv::Mat& mask);

}  // namespace syncap::segmentation
