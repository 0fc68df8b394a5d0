#include "options.hpp"

#include <arpa/inet.h>

#include <array>
#include <charconv>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "syncap/cli/options.hpp"
#include "syncap/trigger/gpiosim.h"

namespace syncap::fakecam {
namespace {

constexpr std::size_t kMaxSerial = 15;  // GigE Vision keeps 16 bytes with the NUL
constexpr std::int64_t kMaxDelayMs = 60'000;
constexpr std::uint64_t kMaxCacheMb = 1'000'000;
constexpr std::uint32_t kMaxLinkMbps = 100'000;

template <class T>
std::optional<T> parse_integer(std::string_view text, T min, T max) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || value < min ||
      value > max) {
    return std::nullopt;
  }
  return value;
}

// The last octet when text is an IPv4 address on the loopback network 127.0.0.0/8.
std::optional<unsigned> loopback_last_octet(const std::string& text) {
  in_addr address{};
  if (inet_pton(AF_INET, text.c_str(), &address) != 1) return std::nullopt;
  const std::uint32_t host = ntohl(address.s_addr);
  if (host >> 24 != 127) return std::nullopt;
  return host & 0xffu;
}

TriggerSpec parse_trigger(std::string_view text) {
  if (text == "software") return {};
  constexpr std::string_view prefix = "gpiosim:";
  const std::size_t colon = text.rfind(':');
  if (!text.starts_with(prefix) || colon < prefix.size()) {
    throw std::invalid_argument("use software or gpiosim:NAME:LINE");
  }
  TriggerSpec spec{TriggerSpec::Kind::gpiosim,
                   std::string(text.substr(prefix.size(), colon - prefix.size())), 0};
  if (!syncap_gpiosim_name_is_valid(spec.chip.c_str())) {
    throw std::invalid_argument("'" + spec.chip + "' is not a valid chip name (A-Z a-z 0-9 . _ -)");
  }
  const auto line =
      parse_integer<unsigned>(text.substr(colon + 1), 0, SYNCAP_GPIOSIM_NUM_LINES - 1);
  if (!line) throw std::invalid_argument("LINE must be 0 to 63");
  spec.line = *line;
  return spec;
}

struct Parser {
  Options options;
  std::string drop_text;
  bool has_drop = false;

  // Applies one option with its value; throws std::invalid_argument saying why it is wrong.
  void apply(std::string_view name, std::string_view value) {
    if (name == "--address") {
      options.address = std::string(value);
      if (!loopback_last_octet(options.address)) {
        throw std::invalid_argument("must be an IPv4 address on the loopback, 127.x.y.z");
      }
    } else if (name == "--images") {
      options.images = std::string(value);
    } else if (name == "--serial") {
      options.serial = std::string(value);
      if (value.empty() || value.size() > kMaxSerial) {
        throw std::invalid_argument("must be 1 to 15 characters");
      }
    } else if (name == "--trigger") {
      options.trigger = parse_trigger(value);
    } else if (name == "--drop") {
      drop_text = std::string(value);
      has_drop = true;
      (void)DropPolicy::parse(value, 0);  // checks the syntax now, naming the option
    } else if (name == "--seed") {
      options.seed = require(parse_integer<std::uint64_t>(value, 0, UINT64_MAX), "not a number");
    } else if (name == "--delay-ms") {
      options.delay_ms = require(parse_integer<std::int64_t>(value, 0, kMaxDelayMs),
                                 "must be 0 to 60000 milliseconds");
    } else if (name == "--start-frame") {
      options.start_frame =
          require(parse_integer<std::uint64_t>(value, 0, UINT64_MAX / 2), "not a frame number");
    } else if (name == "--cache-mb") {
      options.cache_mb =
          require(parse_integer<std::uint64_t>(value, 0, kMaxCacheMb), "must be 0 to 1000000 MiB");
    } else if (name == "--link-mbps") {
      options.link_mbps = require(parse_integer<std::uint32_t>(value, 0, kMaxLinkMbps),
                                  "must be 0 (unpaced) to 100000 Mbit/s");
    } else {
      throw std::logic_error("unhandled option");
    }
  }

  template <class T>
  static T require(std::optional<T> value, const char* why) {
    if (!value) throw std::invalid_argument(why);
    return *value;
  }
};

// The options with a value: name, value in --help, meaning.
constexpr std::array<std::array<const char*, 3>, 10> kValueOptions{{
    {"--address", "A",
     "required: IPv4 address on the loopback to serve on (127.0.0.2-33\nin hil/netns-run)"},
    {"--images", "DIR", "required: the images; all of one size, 8-bit single channel"},
    {"--serial", "NAME", "serial number, 1-15 characters (default SYNCAP-FAKE-<octet>)"},
    {"--trigger", "SOURCE",
     "software (default): one frame per TriggerSoftware command;\n"
     "gpiosim:NAME:LINE: one frame per rising edge of LINE on the\n"
     "shared simulated chip NAME (syncap-trigger --chip sim:NAME)"},
    {"--drop", "LIST|RATE", "leave out frames 3,17,40-45, or a rate: 0.05 or 5% (default none)"},
    {"--seed", "N", "seed of a drop rate (default 1)"},
    {"--delay-ms", "N", "send each frame N ms after its trigger (default 0)"},
    {"--start-frame", "K", "frame number of the first trigger (default 0)"},
    {"--cache-mb", "N", "keep up to N MiB of decoded images in memory (default 256)"},
    {"--link-mbps", "N",
     "send frames no faster than a link of N Mbit/s, as a GigE\ncamera does (default 1000; 0: "
     "unpaced)"},
}};

// The values are kept as given and applied after parsing, so that --help wins over a bad one.
void add_options(CLI::App& app, Parser& parser, std::map<std::string, std::string>& given) {
  for (const auto& [name, metavar, meaning] : kValueOptions) {
    app.add_option_function<std::string>(
           name, [&given, name](const std::string& value) { given[name] = value; }, meaning)
        ->option_text(metavar);
  }
  app.add_flag("--loop", parser.options.loop,
               "frame f shows image first + (f - first) mod (number of\n"
               "images): a short render serves a long run (soak)");
  app.add_flag("--quiet", parser.options.quiet, "no start line and no summary");
}

// Applies the values, checks what only the whole command line can tell and fills in the derived
// values; throws CLI::ValidationError naming the option and the value.
void apply_and_finish(Parser& parser, const std::map<std::string, std::string>& given) {
  for (const auto& [name, value] : given) {
    try {
      parser.apply(name, value);
    } catch (const std::invalid_argument& why) {
      throw CLI::ValidationError("invalid " + name + " '" + value + "': " + why.what());
    }
  }
  Options& options = parser.options;
  if (options.address.empty())
    throw CLI::ValidationError("missing --address (e.g. --address 127.0.0.2)");
  if (options.images.empty()) throw CLI::ValidationError("missing --images DIR");
  if (options.serial.empty()) {
    options.serial = "SYNCAP-FAKE-" + std::to_string(*loopback_last_octet(options.address));
  }
  if (parser.has_drop) options.drop = DropPolicy::parse(parser.drop_text, options.seed);
}

constexpr const char* kDescription =
    "usage: syncap-fakecam --address 127.0.0.X --images DIR [OPTIONS]\n"
    "Serves the 8-bit images DIR/<prefix><frame number>.pgm|.png as a GigE Vision camera\n"
    "(Aravis fake camera) on the address, one frame per trigger. Run it inside\n"
    "hil/netns-run. See docs/design/fakecam.md.\n";

constexpr const char* kFooter =
    "Exit status: 0 after SIGINT/SIGTERM; 1 for bad input or a runtime failure (message on\n"
    "stderr, nothing served); 2 for wrong arguments (message naming the option and the value).";

}  // namespace

std::string TriggerSpec::describe() const {
  if (kind == Kind::software) return "software";
  return "gpiosim:" + chip + ":" + std::to_string(line);
}

ParsedOptions parse_options(std::span<const char* const> arguments) {
  Parser parser;
  std::map<std::string, std::string> given;
  cli::App app("syncap-fakecam", kDescription, kFooter);
  add_options(app, parser, given);
  const std::vector<std::string> args(arguments.begin(), arguments.end());
  const auto stop = cli::try_parse(app, args, [&] { apply_and_finish(parser, given); });
  if (!stop) return {ParsedOptions::Result::run, std::move(parser.options), {}};
  if (stop->help) return {ParsedOptions::Result::help, {}, {}};
  return {ParsedOptions::Result::invalid, {}, stop->error};
}

std::string usage() {
  Parser parser;
  std::map<std::string, std::string> given;
  cli::App app("syncap-fakecam", kDescription, kFooter);
  add_options(app, parser, given);
  return app.help();
}

}  // namespace syncap::fakecam
