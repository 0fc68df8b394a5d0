// The body fit stage on frames whose hull surface is a posed body's (points of known truth): the
// first frame starts the body automatically, the next are tracked, a frame whose body jumped
// away loses the track and starts again on its own points; a frame without points is flagged
// and the pipeline goes on; the message carries the joints in the order the .lcm file names.
#include "reconstruction/body_fit_stage.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "body/hanim_model.hpp"
#include "body_scenes.hpp"
#include "io/frame_json.hpp"
#include "outputs/body_message_stage.hpp"
#include "outputs/search_region_stage.hpp"
#include "sensor/test_cameras.hpp"
#include "syncap/body_frame_t.hpp"

namespace syncap::reconstruction {
namespace {

using fitting::PoseVector;

class BodyFitStageTest : public ::testing::Test {
 protected:
  // A frame group whose hull surface is the body of pose x (the hull's points, exact but for
  // 2 mm of noise).
  pipeline::FrameWork frame(int64_t number, const PoseVector& x) {
    pipeline::FrameWork work;
    work.group.frame_number = number;
    work.group.trigger = trigger_t{};
    work.ready = std::chrono::steady_clock::now();
    work.hull.emplace();
    const auto body = body::body_frame(parameters_.skeleton(), parameters_.pose(x.data()));
    for (const fitting::SurfacePoint& p : fitting::test::surface_points(body, 30, rng_, 2.0))
      work.hull->surface_mm.push_back(p.position_mm);
    return work;
  }
  // A standing pose: the rest figure at (300, -200), turned to face `heading`.
  PoseVector standing(double heading) const {
    PoseVector x = parameters_.rest();
    x[0] = 300, x[1] = -200, x[5] = heading;
    return x;
  }
  const fitting::PoseParameters parameters_{body::hanim_skeleton()};
  std::mt19937 rng_{4};
};

TEST_F(BodyFitStageTest, StartsOnTheFirstFrameThenTracksAndStartsAgainWhenLost) {
  BodyFitStage stage(body::hanim_skeleton());
  PoseVector truth = standing(0.7);
  for (int64_t f = 0; f < 3; ++f) {
    truth[0] += 30;  // walking along X at 0.9 m/s (30 Hz)
    pipeline::FrameWork work = frame(f, truth);
    stage.process(work);
    ASSERT_TRUE(work.body) << f;
    EXPECT_EQ(work.body->flags, f == 0   ? body_frame_t::FLAG_STARTED
                                : f == 1 ? 0
                                         : body_frame_t::FLAG_TRACKED)
        << f;
    ASSERT_EQ(work.body->parameters.size(), std::size_t{fitting::kPoseParameterCount});
    PoseVector fitted;
    std::copy(work.body->parameters.begin(), work.body->parameters.end(), fitted.begin());
    EXPECT_LT(fitting::test::joint_rms_mm(parameters_, fitted, truth), 10.0) << f;
    // The joints: the root's centre first, named; the fit's points nearly all kept.
    ASSERT_EQ(work.body->joints_mm.size(), 19u);
    EXPECT_EQ(work.body->joint_names.front(), "HumanoidRoot");
    EXPECT_LT((work.body->joints_mm[0] - Eigen::Vector3d(truth[0], truth[1], truth[2])).norm(),
              10.0);
    EXPECT_GT(work.body->points_kept, 0.95 * work.body->points);
  }
  // The person is suddenly 1 m away (a second person, a wrong frame): the tracked fit keeps too
  // few points, and the frame's own points start the body there.
  truth[1] += 1000;
  pipeline::FrameWork jumped = frame(3, truth);
  stage.process(jumped);
  EXPECT_EQ(jumped.body->flags,
            body_frame_t::FLAG_TRACKED | body_frame_t::FLAG_LOST | body_frame_t::FLAG_STARTED);
  EXPECT_LT((jumped.body->joints_mm[0] - Eigen::Vector3d(truth[0], truth[1], truth[2])).norm(),
            15.0);
  EXPECT_EQ(stage.stats().starts, 2);
  EXPECT_EQ(stage.stats().tracked, 3);
  EXPECT_EQ(stage.stats().lost, 1);
  EXPECT_NE(stage.summary().find("2 starts (0 found no body), 3 frames tracked, 1 lost"),
            std::string::npos)
      << stage.summary();
}

TEST_F(BodyFitStageTest, AFrameWithoutPointsIsFlaggedAndNothingIsFitted) {
  BodyFitStage stage(body::hanim_skeleton());
  pipeline::FrameWork no_silhouettes;  // no hull stage output at all: not the stage's business
  stage.process(no_silhouettes);
  EXPECT_FALSE(no_silhouettes.body);
  pipeline::FrameWork failed = frame(7, standing(0));
  failed.hull->surface_mm.resize(10);  // a failed or tiny hull
  failed.group.trigger.reset();
  stage.process(failed);
  ASSERT_TRUE(failed.body);
  EXPECT_EQ(failed.body->flags, body_frame_t::FLAG_NO_HULL | body_frame_t::FLAG_NO_TRIGGER);
  EXPECT_TRUE(failed.body->parameters.empty());
  EXPECT_EQ(stage.stats().no_hull, 1);
  // A hull that is no standing person (a flat heap on the floor): no start, said why.
  pipeline::FrameWork flat = frame(8, standing(0));
  for (Eigen::Vector3d& p : flat.hull->surface_mm) p.z() *= 0.1;
  stage.process(flat);
  EXPECT_EQ(flat.body->flags, body_frame_t::FLAG_NO_START);
  EXPECT_NE(stage.summary().find("frame 8: no start: the points are"), std::string::npos)
      << stage.summary();
}

// A start that found no body is tried again start_retry_frames later; the frames between cost
// nothing and are flagged; a person who appears meanwhile is started at the next attempt.
TEST_F(BodyFitStageTest, AFailedStartIsRetriedAtTheStatedInterval) {
  BodyFitStageOptions options;
  options.start_retry_frames = 3;
  options.start_budget_ms = 0;  // the interval alone, whatever a start costs on this machine
  BodyFitStage stage(body::hanim_skeleton(), options);
  for (int64_t f = 20; f < 27; ++f) {
    pipeline::FrameWork work = frame(f, standing(0.3));
    if (f < 24) {
      for (Eigen::Vector3d& p : work.hull->surface_mm) p.z() *= 0.1;  // no standing person yet
    }
    stage.process(work);
    ASSERT_TRUE(work.body) << f;
    const bool attempt = f == 20 || f == 23 || f == 26;
    if (f < 26) {
      EXPECT_EQ(work.body->flags, body_frame_t::FLAG_NO_START) << f;
      if (!attempt) {
        EXPECT_LT(work.body->fit_us, 1000.0) << f;  // no fit at all
      }
    } else {
      EXPECT_EQ(work.body->flags, body_frame_t::FLAG_STARTED) << f;
    }
  }
  EXPECT_EQ(stage.stats().no_start, 2);     // frames 20, 23
  EXPECT_EQ(stage.stats().start_waits, 4);  // 21, 22, 24, 25
  EXPECT_EQ(stage.stats().starts, 1);       // 26
  EXPECT_NE(stage.summary().find("frame 23: no start: "), std::string::npos) << stage.summary();
  EXPECT_NE(stage.summary().find("; next attempt at frame 26"), std::string::npos)
      << stage.summary();
  EXPECT_NE(stage.summary().find("4 frames waited for the next start (after a start that found "
                                 "no body, the next 3 frames or more"),
            std::string::npos)
      << stage.summary();
}

// Failed starts that cost more than the budget a frame wait longer: with a budget of 1 us a
// frame, a start that took a millisecond waits a thousand frames.
TEST_F(BodyFitStageTest, ExpensiveFailedStartsWaitLongerThanTheInterval) {
  BodyFitStageOptions options;
  options.start_retry_frames = 3;
  options.start_budget_ms = 1e-3;
  BodyFitStage stage(body::hanim_skeleton(), options);
  for (int64_t f = 20; f < 30; ++f) {
    pipeline::FrameWork work = frame(f, standing(0.3));
    if (f == 20) {
      for (Eigen::Vector3d& p : work.hull->surface_mm) p.z() *= 0.1;  // no standing person
    }
    stage.process(work);
    EXPECT_EQ(work.body->flags, body_frame_t::FLAG_NO_START) << f;  // the person waits too
  }
  EXPECT_EQ(stage.stats().no_start, 1);
  EXPECT_EQ(stage.stats().start_waits, 9);
  EXPECT_GT(stage.next_start_frame(), 30);
}

TEST_F(BodyFitStageTest, TheMessageAndTheJsonLineCarryThePose) {
  BodyFitStage stage(body::hanim_skeleton());
  pipeline::FrameWork work = frame(42, standing(-0.4));
  stage.process(work);
  ASSERT_TRUE(work.body);
  // The message's joint order is the one its .lcm file documents, and the stage's.
  const std::vector<std::string> names = parameters_.reported_joint_names();
  std::ifstream lcm(std::string(SYNCAP_SOURCE_DIR) + "/proto/msg/body_frame_t.lcm");
  std::stringstream text;
  text << lcm.rdbuf();
  std::string documented = std::regex_replace(text.str(), std::regex("\n *//"), "");
  documented = documented.substr(documented.find("in this order: ") + 15);
  documented = documented.substr(0, documented.find(" ("));
  std::string joined;
  for (const std::string& n : names) joined += (joined.empty() ? "" : ", ") + n;
  EXPECT_EQ(documented, joined);
  EXPECT_EQ(work.body->joint_names, names);

  std::vector<body_frame_t> sent;
  outputs::BodyMessageStage message([&sent](const body_frame_t& m) { sent.push_back(m); });
  message.process(work);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].frame_number, 42);
  EXPECT_EQ(sent[0].flags, body_frame_t::FLAG_STARTED);
  EXPECT_EQ(sent[0].points, static_cast<int>(work.hull->surface_mm.size()));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(sent[0].joint_mm[18][k], work.body->joints_mm[18][k], 1e-3);
  EXPECT_FLOAT_EQ(sent[0].parameters[5], static_cast<float>(work.body->parameters[5]));
  // The fit's precision rides along: positive sigmas for every joint and parameter.
  ASSERT_EQ(work.body->joint_sigmas_mm.size(), 19u);
  ASSERT_EQ(work.body->parameter_sigmas.size(), 60u);
  EXPECT_GT(sent[0].sigma0, 0.0f);
  for (int j = 0; j < 19; ++j) {
    EXPECT_GT(sent[0].joint_sigma_mm[j], 0.0f) << names[static_cast<std::size_t>(j)];
    EXPECT_FLOAT_EQ(sent[0].joint_sigma_mm[j],
                    static_cast<float>(work.body->joint_sigmas_mm[static_cast<std::size_t>(j)]));
  }
  EXPECT_FLOAT_EQ(sent[0].parameter_sigmas[59],
                  static_cast<float>(work.body->parameter_sigmas[59]));

  const io::FrameRecord back = io::parse_frame_line(io::frame_line(work, false), "test");
  ASSERT_TRUE(back.body);
  EXPECT_EQ(back.body->flags, work.body->flags);
  EXPECT_EQ(back.body->points_kept, work.body->points_kept);
  ASSERT_EQ(back.body->joints_mm.size(), 19u);
  for (std::size_t j = 0; j < back.body->joint_names.size(); ++j) {
    const auto at = std::find(names.begin(), names.end(), back.body->joint_names[j]);
    ASSERT_NE(at, names.end());
    EXPECT_LT((back.body->joints_mm[j] -
               work.body->joints_mm[static_cast<std::size_t>(at - names.begin())])
                  .norm(),
              1e-3);
  }
  EXPECT_NEAR(back.body->parameters[5], work.body->parameters[5], 1e-6);
  ASSERT_EQ(back.body->joint_sigmas_mm.size(), 19u);
  for (std::size_t j = 0; j < back.body->joint_names.size(); ++j) {
    const auto at = std::find(names.begin(), names.end(), back.body->joint_names[j]);
    EXPECT_NEAR(back.body->joint_sigmas_mm[j],
                work.body->joint_sigmas_mm[static_cast<std::size_t>(at - names.begin())], 1e-3);
  }
  ASSERT_EQ(back.body->parameter_sigmas.size(), 60u);
  EXPECT_NEAR(back.body->parameter_sigmas[7], work.body->parameter_sigmas[7], 1e-6);
  EXPECT_NEAR(back.body->sigma0, work.body->sigma0, 1e-4);
}

// After a fit, every camera gets the body's search region for the frames after it; a frame
// without a fit sends nothing (the regions sent before expire).
TEST(SearchRegionStage, SendsEachCameraTheFittedBodysRegion) {
  sensor::CameraModel a = sensor::test::basler_camera();
  sensor::CameraModel b = a;
  b.id = 7;
  b.exterior = sensor::test::looking_at({-4000, 1500, 2200}, {0, 0, 1000});
  outputs::SearchRegionStageOptions options;
  options.lead = 2;
  options.valid_frames = 5;
  std::vector<clip_polygon_t> sent;
  outputs::SearchRegionStage stage({a, b}, options,
                                   [&sent](clip_polygon_t& m) { sent.push_back(m); });
  pipeline::FrameWork work;
  work.group.frame_number = 40;
  stage.process(work);  // no body
  EXPECT_TRUE(sent.empty());
  const fitting::PoseParameters parameters(body::hanim_skeleton());
  const auto rest = parameters.rest();
  work.body.emplace();
  work.body->parameters.assign(rest.begin(), rest.end());
  stage.process(work);
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(stage.frames_sent(), 1);
  EXPECT_EQ(sent[1].camera_id, 7);
  for (const clip_polygon_t& m : sent) {
    EXPECT_EQ(m.region, clip_polygon_t::REGION_SEARCH);
    EXPECT_EQ(m.frame_number, 42);
    EXPECT_EQ(m.valid_frames, 5);
    EXPECT_GE(m.num_points, 3);
    EXPECT_EQ(m.x.size(), static_cast<std::size_t>(m.num_points));
  }
  // The region holds the body: the root (pelvis, ~1 m up) projects inside camera 7's polygon.
  std::vector<cv::Point> polygon;
  for (int i = 0; i < sent[1].num_points; ++i) polygon.emplace_back(sent[1].x[i], sent[1].y[i]);
  const Eigen::Vector2d pelvis = b.project(Eigen::Vector3d(0, 0, 1000)).pixel;
  EXPECT_GT(cv::pointPolygonTest(polygon, cv::Point2f(float(pelvis.x()), float(pelvis.y())), false),
            0);
}

}  // namespace
}  // namespace syncap::reconstruction
