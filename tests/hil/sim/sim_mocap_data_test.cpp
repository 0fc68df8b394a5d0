// The shipped mocap scenario on the real marker trajectories (../shared/data/motion/real-markers):
// every marker of the Qualisys walk is a target, the occluders hide some of them from some
// cameras, and every visible spot is in the image at a size the edges detect.
#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>

#include "camera_rig.hpp"
#include "render.hpp"
#include "scenario.hpp"
#include "sequence.hpp"
#include "syncap_test_data.hpp"

namespace syncap::sim {
namespace {

TEST(SimMocapData, QualisysWalkMarkersAreTargetsAndTheBodyHidesSome) {
  SYNCAP_REQUIRE_DATA(c3d, "motion/real-markers/Qualisys.c3d");
  Scenario sc = load_scenario(std::filesystem::path(SYNCAP_SOURCE_DIR) / "hil" / "scenarios" /
                              "markers-8cam-qualisys.yaml");
  ASSERT_EQ(sc.phases.size(), 2u);
  PhaseSpec& phase = sc.phases[1];
  ASSERT_EQ(phase.type, "mocap");
  phase.mocap.trajectories = c3d;
  phase.mocap.trajectories_not_found.clear();
  Sequence sequence(sc, [](const PersonSpec&, const Scenario&) { return BodySource(); });
  const FrameState st = sequence.at(sc.phases[0].frames + phase.frames / 2);
  ASSERT_EQ(st.phase, &phase);
  ASSERT_NE(st.target_names, nullptr);
  ASSERT_EQ(st.target_names->size(), 55u);  // the file's markers, no gaps
  std::vector<int> all(55);
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(st.target_ids, all);
  EXPECT_GE(st.content.body.size(), 13u);  // every occluder drawn (no gaps)

  long pairs = 0, hidden = 0;
  for (const auto& camera : build_rig(sc)) {
    const RenderedView out = render_view(make_view(camera, sc), st.content, sc.image, 1);
    ASSERT_EQ(out.spheres.size(), 55u);
    for (std::size_t t = 0; t < out.spheres.size(); ++t) {
      const SphereTruth& s = out.spheres[t];
      ++pairs;
      if (!s.visible) {
        ++hidden;
        continue;
      }
      EXPECT_GE(s.pixel.x(), 0) << st.target_names->at(t) << " camera " << camera.id;
      EXPECT_LE(s.pixel.x(), sc.cameras.width_px - 1);
      EXPECT_GE(s.pixel.y(), 0);
      EXPECT_LE(s.pixel.y(), sc.cameras.height_px - 1);
      EXPECT_GE(s.radius_px, 1.0) << st.target_names->at(t) << " camera " << camera.id;
      EXPECT_LE(s.radius_px, 4.0) << st.target_names->at(t) << " camera " << camera.id;
    }
  }
  const double share = static_cast<double>(hidden) / static_cast<double>(pairs);
  ::testing::Test::RecordProperty("hidden_share", std::to_string(share));
  EXPECT_GT(share, 0.05);
  EXPECT_LT(share, 0.60);
}

}  // namespace
}  // namespace syncap::sim
