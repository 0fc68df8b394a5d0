#include "ctl_command.hpp"

#include <lcm/lcm-cpp.hpp>

#include <CLI/CLI.hpp>
#include <charconv>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "grouping/arrival_tally.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/command_auth.hpp"
#include "syncap/proto/subscriber.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kCtlName = "syncap ctl";
constexpr const char* kActions =
    "ACTION: start | stop | shutdown | train-background FRAMES | threshold DN (0: from the "
    "histogram) | roi X,Y,W,H | roi full | exposure US | gain DB | patches N (the person's "
    "grey values every Nth frame, for the host's --surface; 0: none) | status (send nothing, "
    "show the heartbeats)";

template <class Number>
Number parse_number(const std::string& text, Number low, Number high, const std::string& what) {
  Number value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !(value >= low && value <= high)) {
    throw std::invalid_argument(what + " '" + text + "': expected a number " + std::to_string(low) +
                                ".." + std::to_string(high));
  }
  return value;
}

void set_roi(edge_command_t& c, const std::string& text) {
  if (text == "full") return;  // width and height 0: the whole sensor
  std::vector<int16_t> v;
  std::size_t at = 0;
  bool more = true;  // text left after the last comma
  while (more) {
    const std::size_t comma = text.find(',', at);
    more = comma != std::string::npos;
    const std::string part = text.substr(at, more ? comma - at : std::string::npos);
    v.push_back(parse_number<int16_t>(part, 0, INT16_MAX, "roi X,Y,W,H"));
    at = comma + 1;
  }
  if (v.size() != 4)
    throw std::invalid_argument("roi '" + text + "': expected X,Y,W,H in pixels, or full");
  c.roi_x = v[0];
  c.roi_y = v[1];
  c.roi_width = v[2];
  c.roi_height = v[3];
}

const char* result_text(int8_t result) {
  return result == camera_status_t::COMMAND_ACCEPTED
             ? "accepted"
             : proto::describe(static_cast<proto::CommandCheck>(result));
}

std::string status_line(const camera_status_t& s) {
  std::string line = std::string(grouping::state_name(s.state)) + ", last frame " +
                     std::to_string(s.last_frame_number) + ", " +
                     std::to_string(s.commands_accepted) + " commands obeyed, " +
                     std::to_string(s.commands_rejected) + " refused";
  if (!s.message.empty()) line += ": " + s.message;
  return line;
}

struct CtlArgs {
  std::vector<std::string> action;
  std::string key_path;
  std::string camera = "all";
  std::string lcm_url = proto::kDefaultLcmUrl;
  double wait_s = 2.5;
};

void add_ctl_options(CLI::App& app, CtlArgs& a) {
  app.add_option("action", a.action, "the action and its value")->required();
  app.add_option("--command-key", a.key_path, "the installation's command key (syncap keygen)");
  app.add_option("--camera", a.camera, "a camera id 0..99, or all (default)");
  app.add_option("--lcm-url", a.lcm_url, "LCM provider (default " + a.lcm_url + ")");
  app.add_option("--wait-s", a.wait_s,
                 "how long to wait for the answers (default 2.5: the heartbeat comes every "
                 "second, a refusal with the next one)")
      ->check(cli::number_in(0.1, 600.0));
}

// Parses into `a`; an exit status when the run is over already (help, usage error).
std::optional<int> parse_ctl_args(std::span<const std::string> args, CtlArgs& a, std::ostream& out,
                                  std::ostream& err) {
  cli::App app(kCtlName,
               "Sends the edges a command signed with the installation's key and shows each "
               "camera's answer from its heartbeats (docs/design/security.md).\n" +
                   std::string(kActions),
               "Exit status: 0 every camera that answered obeyed, 1 otherwise, 2 a usage error.");
  add_ctl_options(app, a);
  app.deprecated_name("--key", "--command-key");
  return cli::parse(app, args, out, err);
}

int16_t camera_of(const std::string& text) {
  if (text == "all") return edge_command_t::ALL_CAMERAS;
  return parse_number<int16_t>(text, 0, proto::kMaxCameraId, "--camera");
}

// Prints each camera's answer; the exit status: 0 when every camera that answered obeyed (and
// the one asked for answered), 1 otherwise.
int report(const Acknowledgements& acks, int16_t camera, std::ostream& out) {
  bool all_obeyed = true;
  int answered = 0;
  for (const auto& [id, status] : acks.heard()) {
    if (camera != edge_command_t::ALL_CAMERAS && id != camera) continue;
    const std::optional<int8_t> answer = acks.answer(id);
    if (answer) ++answered;
    all_obeyed = all_obeyed && answer == camera_status_t::COMMAND_ACCEPTED;
    out << "camera " << id << ": "
        << (answer ? result_text(*answer) : "no answer (its heartbeat came, the command did not?)")
        << " (" << status_line(status) << ")\n";
  }
  if (camera != edge_command_t::ALL_CAMERAS && !acks.heard().contains(camera))
    out << "camera " << camera << ": no heartbeat (is its edge running on this LCM URL?)\n";
  if (answered == 0) out << "no camera answered\n";
  return answered > 0 && all_obeyed ? kExitOk : kExitReportedErrors;
}

// Listens to the heartbeats for `wait_s`, or until `done` says so.
void listen(lcm::LCM& lcm, double wait_s, const std::function<bool()>& done) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<int64_t>(wait_s * 1000));
  while (!done()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    lcm.handleTimeout(static_cast<int>(std::min<int64_t>(left.count(), 100)));
  }
}

int show_status(lcm::LCM& lcm, proto::Subscriber& subscriber, const CtlArgs& a, int16_t camera,
                std::ostream& out) {
  std::map<int, camera_status_t> heard;
  subscriber.subscribe<camera_status_t>(
      std::string(proto::kStatusChannelPrefix) + ".*",
      [&](const camera_status_t& s, const std::string&) { heard[s.camera_id] = s; });
  listen(lcm, a.wait_s, [] { return false; });
  for (const auto& [id, status] : heard) {
    if (camera == edge_command_t::ALL_CAMERAS || id == camera)
      out << "camera " << id << ": " << status_line(status) << '\n';
  }
  if (heard.empty()) out << "no heartbeat in " << a.wait_s << " s\n";
  return heard.empty() ? kExitReportedErrors : kExitOk;
}

}  // namespace

edge_command_t command_of_action(const std::string& action, std::span<const std::string> values) {
  edge_command_t c{};
  const auto expect_values = [&](std::size_t want) {
    if (values.size() != want)
      throw std::invalid_argument(action + " takes " + std::to_string(want) + " value(s)");
  };
  const auto value = [&]() -> const std::string& {
    expect_values(1);
    return values[0];
  };
  if (action == "start" || action == "stop" || action == "shutdown") {
    expect_values(0);
    c.command = action == "start"  ? edge_command_t::START
                : action == "stop" ? edge_command_t::STOP
                                   : edge_command_t::SHUTDOWN;
  } else if (action == "train-background") {
    c.command = edge_command_t::TRAIN_BACKGROUND;
    c.int_value = parse_number<int64_t>(value(), 1, 10000, "train-background FRAMES");
  } else if (action == "threshold") {
    c.command = edge_command_t::SET_THRESHOLD;
    c.int_value = parse_number<int64_t>(value(), 0, 255, "threshold DN");
  } else if (action == "patches") {
    c.command = edge_command_t::SET_PATCH_EVERY;
    c.int_value = parse_number<int64_t>(value(), 0, 100000, "patches N");
  } else if (action == "roi") {
    c.command = edge_command_t::SET_ROI;
    set_roi(c, value());
  } else if (action == "exposure") {
    c.command = edge_command_t::SET_EXPOSURE;
    c.real_value = parse_number<double>(value(), 1, 1e7, "exposure US");
  } else if (action == "gain") {
    c.command = edge_command_t::SET_GAIN;
    c.real_value = parse_number<double>(value(), 0, 100, "gain DB");
  } else {
    throw std::invalid_argument("unknown action '" + action + "'");
  }
  return c;
}

bool Acknowledgements::take(const camera_status_t& status) {
  heard_[status.camera_id] = status;
  if (status.last_command_sender != sender_ || status.last_command_sequence != sequence_)
    return false;
  answers_[status.camera_id] = status.last_command_result;
  return true;
}

std::optional<int8_t> Acknowledgements::answer(int camera_id) const {
  const auto it = answers_.find(camera_id);
  if (it == answers_.end()) return std::nullopt;
  return it->second;
}

int ctl_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  CtlArgs a;
  if (const auto status = parse_ctl_args(args, a, out, err)) return *status;
  edge_command_t command{};
  int16_t camera = 0;
  try {
    camera = camera_of(a.camera);
    if (a.action[0] != "status")
      command = command_of_action(a.action[0], std::span(a.action).subspan(1));
    if (a.action[0] != "status" && a.key_path.empty())
      throw std::invalid_argument(
          "--command-key FILE is required to command the edges (syncap keygen)");
  } catch (const std::invalid_argument& e) {
    err << kCtlName << ": " << e.what() << '\n' << kActions << '\n';
    return kExitUsage;
  }
  std::optional<proto::CommandSigner> signer;
  try {
    if (!a.key_path.empty()) signer.emplace(proto::CommandKey::load(a.key_path));
  } catch (const proto::CommandKeyError& e) {
    err << kCtlName << ": --command-key " << e.what() << '\n';
    return kExitUsage;
  }
  lcm::LCM lcm(proto::receiving_lcm_url(a.lcm_url));
  if (!lcm.good()) {
    err << kCtlName << ": cannot open LCM at " << a.lcm_url << '\n';
    return kExitUsage;
  }
  proto::Subscriber subscriber(lcm,
                               [&](const std::string& e) { err << kCtlName << ": " << e << '\n'; });
  if (a.action[0] == "status") return show_status(lcm, subscriber, a, camera, out);

  command.camera_id = camera;
  signer->sign(command);
  Acknowledgements acks(signer->sender(), command.sequence);
  subscriber.subscribe<camera_status_t>(
      std::string(proto::kStatusChannelPrefix) + ".*",
      [&](const camera_status_t& s, const std::string&) { acks.take(s); });
  lcm.publish(proto::kEdgeCommandChannel, &command);
  // One camera: done when it answered. All: every camera heard within the wait is shown.
  listen(lcm, a.wait_s,
         [&] { return camera != edge_command_t::ALL_CAMERAS && acks.answer(camera).has_value(); });
  return report(acks, camera, out);
}

int keygen_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  std::string path = "/etc/syncap/command.key";
  bool force = false;
  cli::App app("syncap keygen",
               "Creates the installation's command key: 32 random bytes as hexadecimal, in a "
               "file only its owner may read (mode 0600). Copy it to every edge board and the "
               "host over a trusted channel (docs/design/security.md).",
               "Exit status: 0 written, 2 a usage error or a key that cannot be written.");
  app.add_option("--out", path, "the key file (default " + path + ")");
  app.add_flag("--force", force, "replace an existing key (every board then needs the new one)");
  if (const std::optional<int> status = cli::parse(app, args, out, err)) return *status;
  try {
    proto::CommandKey::generate().save(path, force);
  } catch (const proto::CommandKeyError& e) {
    err << "syncap keygen: " << e.what() << '\n';
    return kExitUsage;
  }
  out << "syncap keygen: wrote " << path << " (mode 0600)\n";
  return kExitOk;
}

}  // namespace syncap::tools
