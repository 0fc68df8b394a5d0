// What syncap-host prints: a line per frame group (unless --quiet) and the summary at the end.
#pragma once

#include <ostream>
#include <string>

#include "grouping/arrival_tally.hpp"
#include "outputs/marker_message_stage.hpp"
#include "pipeline/host_node.hpp"
#include "reconstruction/body_fit_stage.hpp"
#include "reconstruction/hull_stage.hpp"
#include "reconstruction/marker_stage.hpp"
#include "reconstruction/rigid_set_stage.hpp"
#include "reconstruction/surface_stage.hpp"
#include "syncap/proto/subscriber.hpp"

namespace syncap::host_app {

// "host time per group: p50 ... ms, p99 ... ms; its CPU time ...\n": the wall time from a group's
// hand-out to its last stage's end and the worker's CPU time in the stages.
std::string host_time_line(const pipeline::HostNodeStats& stats);

// Counts of the receiving side, kept by host_main.
struct Arrivals {
  long triggers = 0, blob_parts = 0, silhouette_parts = 0, patch_parts = 0, rejected = 0;
  grouping::ArrivalTally tally;
};

struct SummaryInputs {
  const pipeline::HostNode& node;
  const proto::Subscriber& subscriber;
  const Arrivals& arrivals;
  const reconstruction::MarkerStage* markers = nullptr;         // with --calibration
  const outputs::MarkerMessageStage* marker_message = nullptr;  // with --calibration
  const reconstruction::RigidSetStage* rigid_sets = nullptr;    // with --rigid-sets
  const reconstruction::HullStage* hull = nullptr;              // with --hull
  const reconstruction::BodyFitStage* body = nullptr;           // with --body
  const reconstruction::SurfaceStage* surface = nullptr;        // with --surface
};

void print_summary(const SummaryInputs& in, std::ostream& out);

}  // namespace syncap::host_app
