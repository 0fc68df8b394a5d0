// The person of a scenario: the H-Anim body of host/src/body driven by the phase's BVH motion,
// placed inside the scenario's capture volume.
#pragma once

#include "sequence.hpp"

namespace syncap::sim {

// Loads person.bvh (errors name file and line) and returns the body at any time. Motion past
// the clip's end loops.
BodySource open_bvh_body(const PersonSpec& person, const Scenario& scenario);

}  // namespace syncap::sim
