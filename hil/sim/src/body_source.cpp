#include "body_source.hpp"

#include <memory>
#include <stdexcept>

#include "body/bvh.hpp"
#include "body/hanim_model.hpp"
#include "body/pose.hpp"
#include "body/retarget.hpp"

namespace syncap::sim {

BodySource open_bvh_body(const PersonSpec& person, const Scenario& scenario) {
  if (!person.bvh_not_found.empty()) {
    throw std::runtime_error(scenario.file.string() + ": motion " + person.bvh_not_found);
  }
  body::RetargetOptions options;
  options.volume = body::CaptureVolume{scenario.volume_min_mm, scenario.volume_max_mm};
  options.loop = true;
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
