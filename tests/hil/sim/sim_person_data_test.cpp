// The simulator's person driven by the real captured motion (../shared/data/motion).
#include <gtest/gtest.h>

#include "body_source.hpp"
#include "camera_rig.hpp"
#include "render.hpp"
#include "scenario.hpp"
#include "syncap_test_data.hpp"

namespace syncap::sim {
namespace {

// The real captured motion drives the person: rendered silhouettes equal the exact test of every
// pixel against every ellipsoid, in every camera.
TEST(SimPersonData, SilhouettesOfTheRealMotionAreExact) {
  SYNCAP_REQUIRE_DATA(bvh, "motion/mixamo-free.bvh");
  Scenario sc = parse_scenario(R"(
cameras: {count: 4, layout: ring, radius_mm: 3500, height_mm: 1800, width_px: 240, height_px: 180,
          pixel_size_mm: 0.02, c_mm: 4.0, k1: 3.0e-3}
phases:
  - {type: person, frames: 3, bvh: /dev/null}
)",
                               "person.yaml");
  sc.phases[0].person.bvh = bvh;
  const auto rig = build_rig(sc);
  const BodySource body = open_bvh_body(sc.phases[0].person, sc);
  for (double t : {0.0, 1.3, 2.9}) {
    FrameContent content;
    content.room_background = true;
    content.body = body(t).ellipsoids;
    for (const auto& camera : rig) {
      const View view = make_view(camera, sc);
      const RenderedView out = render_view(view, content, sc.image, 1);
      const cv::Mat truth = silhouette_brute_force(view, content.body);
      EXPECT_EQ(cv::countNonZero(out.mask != truth), 0) << "t " << t << " camera " << camera.id;
      EXPECT_GT(cv::countNonZero(truth), 100) << "t " << t << " camera " << camera.id;
    }
  }
}

}  // namespace
}  // namespace syncap::sim
