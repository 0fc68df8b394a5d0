#include "region_sender.hpp"

#include <lcm/lcm-cpp.hpp>

#include <nlohmann/json.hpp>

#include "io/message_json.hpp"
#include "subcommand.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/command_auth.hpp"

namespace syncap::tools {

int send_regions(std::vector<clip_polygon_t> messages, const std::vector<std::string>& notes,
                 const RegionSending& sending, const char* prefix, std::ostream& out,
                 std::ostream& err) {
  std::optional<lcm::LCM> lcm;
  std::optional<proto::CommandSigner> signer;
  if (sending.publish) {
    try {
      signer.emplace(proto::CommandKey::load(sending.key_path));
    } catch (const proto::CommandKeyError& e) {
      err << prefix << "--command-key " << e.what() << '\n';
      return kExitUsage;
    }
    lcm.emplace(sending.lcm_url);
    if (!lcm->good()) {
      err << prefix << "cannot open LCM at " << sending.lcm_url << '\n';
      return kExitUsage;
    }
  }
  for (clip_polygon_t& m : messages) {
    if (signer) signer->sign(m);
    out << nlohmann::ordered_json(m).dump() << '\n';
    if (lcm) lcm->publish(proto::kEdgeClipChannel, &m);
  }
  for (const std::string& note : notes) err << prefix << note << '\n';
  return notes.empty() ? kExitOk : kExitReportedErrors;
}

}  // namespace syncap::tools
