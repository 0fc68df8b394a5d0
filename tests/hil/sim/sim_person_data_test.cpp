// The simulator's person driven by the real captured motion (../shared/data/motion).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "body_source.hpp"
#include "camera_rig.hpp"
#include "render.hpp"
#include "scenario.hpp"
#include "sequence.hpp"
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

// The shipped mocap scenario's markers ride on their segments through the real motion: each
// keeps its place in its segment's axes (the segment moves and turns, the marker with it), and
// about half of the markers' projections are hidden by the body (the far side), none off-image.
TEST(SimPersonData, MarkersRideOnTheirSegmentsAndTheBodyHidesSome) {
  SYNCAP_REQUIRE_DATA(bvh, "motion/mixamo-free.bvh");
  const Scenario sc = load_scenario(std::filesystem::path(SYNCAP_SOURCE_DIR) / "hil" / "scenarios" /
                                    "markers-8cam-body.yaml");
  const PhaseSpec& phase = sc.phases.at(1);
  ASSERT_GE(phase.person.markers.size(), 24u);
  PersonSpec person = phase.person;
  person.bvh = bvh;
  person.bvh_not_found.clear();
  const BodySource body = open_bvh_body(person, sc);
  const auto rig = build_rig(sc);
  long projections = 0, visible = 0;
  for (double t : {0.0, 0.9, 1.8}) {
    const BodyFrame frame = body(t);
    FrameContent content;
    content.body = frame.ellipsoids;
    for (const MarkerSpec& marker : person.markers) {
      const auto centre = marker_centre(frame, marker, person.marker_radius_mm);
      ASSERT_TRUE(centre) << marker.segment;
      const auto index = std::find(frame.segments.begin(), frame.segments.end(), marker.segment) -
                         frame.segments.begin();
      const Ellipsoid& e = frame.ellipsoids.at(static_cast<std::size_t>(index));
      const Eigen::Vector3d local = e.axes.transpose() * (*centre - e.centre_mm);
      // Its direction in the segment's axes is the scenario's (the surface point plus the normal
      // offset stays on the same side of every axis).
      EXPECT_GT(local.normalized().dot(marker.at.normalized()), 0.5) << marker.segment;
      Sphere sphere;
      sphere.centre_mm = *centre;
      sphere.radius_mm = person.marker_radius_mm;
      content.spheres.push_back(sphere);
    }
    for (const auto& camera : rig) {
      const RenderedView out = render_view(make_view(camera, sc), content, sc.image, 1);
      for (const SphereTruth& s : out.spheres) {
        ++projections;
        visible += s.visible;
      }
    }
  }
  const double share = static_cast<double>(visible) / static_cast<double>(projections);
  EXPECT_GT(share, 0.35);
  EXPECT_LT(share, 0.75);
}

}  // namespace
}  // namespace syncap::sim
