#include "app/host_report.hpp"

#include <cstdio>
#include <sstream>

namespace syncap::host_app {
namespace {

void print_grouping(const SummaryInputs& in, std::ostream& out) {
  const pipeline::HostNodeStats s = in.node.stats();
  const grouping::FrameGrouper& g = in.node.grouper();
  const Arrivals& a = in.arrivals;
  out << "host summary: " << s.groups << " frame groups (" << s.complete << " complete, "
      << s.groups - s.complete << " incomplete), " << a.triggers << " triggers, " << a.blob_parts
      << " blob messages, " << a.silhouette_parts << " silhouette parts, "
      << (a.patch_parts > 0 ? std::to_string(a.patch_parts) + " image patch parts, " : "")
      << in.subscriber.malformed() << " malformed, " << a.rejected << " rejected ("
      << g.late_messages() << " late, " << g.foreign_messages() << " from cameras not expected, "
      << g.wrong_channel_messages() << " on another camera's channel, " << g.duplicate_messages()
      << " duplicates), " << g.far_ahead_messages() << " far ahead of the newest frame\n";
  for (const auto& [channel, count] : in.subscriber.malformed_by_channel())
    out << "malformed on " << channel << ": " << count << "\n";
  out << a.tally.summary();
}

void print_reconstruction(const SummaryInputs& in, std::ostream& out) {
  const pipeline::HostNodeStats s = in.node.stats();
  const reconstruction::MarkerStageStats& m = in.markers->stats();
  char line[512];
  std::snprintf(line, sizeof line,
                "host markers: %ld frames, %ld markers (%ld seen by two cameras only), %ld of "
                "%ld blobs in a marker, %ld of cameras outside the calibration, %ld not round "
                "(left out), %ld partly hidden (left out of their marker's position), %ld "
                "merged (left out; %ld points without two other spots dropped)\n",
                m.frames, m.markers, m.two_camera_markers, m.blobs_used, m.blobs,
                m.blobs_of_unknown_cameras, m.blobs_not_round, m.partial_spots_left_out,
                m.merged_spots_left_out, m.merged_points_dropped);
  out << line;
  out << host_time_line(s);
  if (in.marker_message != nullptr && in.marker_message->latency().added() > 0) {
    const auto& latency = in.marker_message->latency().values();
    const auto& host = in.marker_message->host_us().values();
    const auto& cpu = in.marker_message->host_cpu_us().values();
    std::snprintf(line, sizeof line,
                  "latency trigger to marker message: p50 %.3f ms, p99 %.3f ms (%zu frames); the "
                  "host's part p50 %.3f ms, p99 %.3f ms, its CPU time p50 %.3f ms, p99 %.3f ms\n",
                  pipeline::quantile(latency, 0.5), pipeline::quantile(latency, 0.99),
                  in.marker_message->latency().added(), pipeline::quantile(host, 0.5) * 1e-3,
                  pipeline::quantile(host, 0.99) * 1e-3, pipeline::quantile(cpu, 0.5) * 1e-3,
                  pipeline::quantile(cpu, 0.99) * 1e-3);
    out << line;
  }
}

}  // namespace

std::string host_time_line(const pipeline::HostNodeStats& s) {
  char line[512];
  std::snprintf(line, sizeof line,
                "host time per group (grouped to done, the queue's wait included): p50 %.3f ms, "
                "p99 %.3f ms; its CPU time p50 %.3f ms, p99 %.3f ms (%ld groups, %ld dropped by "
                "a full queue)\n",
                pipeline::quantile(s.host_us.values(), 0.5) * 1e-3,
                pipeline::quantile(s.host_us.values(), 0.99) * 1e-3,
                pipeline::quantile(s.host_cpu_us.values(), 0.5) * 1e-3,
                pipeline::quantile(s.host_cpu_us.values(), 0.99) * 1e-3, s.processed, s.dropped);
  return line;
}

void print_summary(const SummaryInputs& in, std::ostream& out) {
  print_grouping(in, out);
  if (in.markers != nullptr) print_reconstruction(in, out);
  if (in.rigid_sets != nullptr) out << in.rigid_sets->summary();
  if (in.hull != nullptr) out << in.hull->summary();
  if (in.body != nullptr) out << in.body->summary();
  if (in.surface != nullptr) out << in.surface->summary();
  out.flush();
}

}  // namespace syncap::host_app
