#include "body_source.hpp"

#include <memory>
#include <stdexcept>

#include "body/bvh.hpp"
#include "body/hanim_model.hpp"
#include "body/pose.hpp"
#include "body/retarget.hpp"
#include "skinned_body.hpp"

namespace syncap::sim {

namespace {

body::RetargetOptions retarget_options(const Scenario& scenario) {
  body::RetargetOptions options;
  options.volume = body::CaptureVolume{scenario.volume_min_mm, scenario.volume_max_mm};
  options.loop = true;
  return options;
}

// The skinned subject driven by the same retargeting: its own skeleton, its skin posed.
BodySource open_mesh_body(const PersonSpec& person, const Scenario& scenario) {
  static const SkinnedHumanAsset asset = load_skinned_human(default_skinned_human_file());
  auto subject = [&] {
    try {
      return make_subject(asset, person.subject);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(scenario.file.string() + ": person.subject: " + e.what());
    }
  };
  auto shared = std::make_shared<const SkinnedSubject>(subject());
  body::RetargetOptions options = retarget_options(scenario);
  options.align_legs = true;  // MakeHuman's rest legs stand about 7 degrees apart
  auto retargeter =
      std::make_shared<body::BvhRetargeter>(shared->skeleton, body::load_bvh(person.bvh), options);
  return [shared, retargeter](double t_s) {
    const body::Pose pose = retargeter->pose_at(t_s);
    const auto positions = body::node_positions(shared->skeleton, pose);
    BodyFrame out;
    for (std::size_t i = 0; i < positions.size(); ++i)
      out.joints.emplace_back(shared->skeleton.nodes()[i].name, positions[i]);
    out.mesh = pose_subject(*shared, pose);
    out.subject = shared->name;
    return out;
  };
}

}  // namespace

BodySource open_bvh_body(const PersonSpec& person, const Scenario& scenario) {
  if (!person.bvh_not_found.empty()) {
    throw std::runtime_error(scenario.file.string() + ": motion " + person.bvh_not_found);
  }
  if (person.model == "mesh") return open_mesh_body(person, scenario);
  const body::RetargetOptions options = retarget_options(scenario);
  auto retargeter = std::make_shared<body::BvhRetargeter>(body::hanim_skeleton(),
                                                          body::load_bvh(person.bvh), options);
  return [retargeter](double t_s) {
    const body::BodyFrame frame = retargeter->body_at(t_s);
    BodyFrame out;
    const auto& nodes = retargeter->skeleton().nodes();
    for (std::size_t i = 0; i < nodes.size(); ++i)
      out.joints.emplace_back(nodes[i].name, frame.positions_mm[i]);
    for (const body::Ellipsoid& e : frame.ellipsoids)
      out.ellipsoids.push_back({e.centre_mm, e.axes, e.radii_mm});
    for (const body::Segment& segment : retargeter->skeleton().segments())
      out.segments.push_back(segment.name);
    return out;
  };
}

}  // namespace syncap::sim
