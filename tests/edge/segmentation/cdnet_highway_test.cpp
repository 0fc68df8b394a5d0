// Medi-picture on the real CDnet 2014 highway set, every frame of the scored range (~5 s).
#include <gtest/gtest.h>

#include "segmentation/cdnet_eval.hpp"
#include "syncap_test_data.hpp"

namespace syncap::edge {
namespace {

TEST(CdnetHighway, MediPictureReachesMeasuredFMeasure) {
  SYNCAP_REQUIRE_DATA(dir, "segmentation/cdnet2014-highway");
  // The options of docs/segmentation.md: the NCC shadow test off (on this scene it takes dark
  // car bodies for shadow), slow update on.
  CdnetEvalOptions options;
  options.medi_picture.remove_shadows = false;
  options.medi_picture.update_rate = 0.02f;
  const CdnetScores scores = evaluate_cdnet(dir, options);
  EXPECT_EQ(scores.scored_frames, 1231);
  // Measured 0.9447 (P 0.9308, R 0.9591); GMM scores 0.924 in the CDnet results.
  EXPECT_GE(scores.f_measure(), 0.94) << "P " << scores.precision() << " R " << scores.recall();
}

}  // namespace
}  // namespace syncap::edge
