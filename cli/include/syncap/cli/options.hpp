// What every program's CLI11 option parsing shares (issue 16): one way to parse and to map
// CLI11's outcomes to the exit rule, and the number checks CLI11's own conversions lack.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace syncap::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 2;  // a usage error or bad input

// A program's parser: `about` above the options in --help, `footer` (the exit statuses) below.
// As the hand-written argv loops did, an option given twice takes the last value.
class App : public CLI::App {
 public:
  App(const std::string& name, const std::string& about, const std::string& footer)
      : CLI::App(about, name) {
    this->footer(footer);
    option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }

  // An old name of an option (docs/reference/cli.md, "Old names"): still taken, on the command
  // line and as a config file's key, as `new_name` with its checks, and said to be deprecated
  // on stderr; not in --help.
  void deprecated_name(const std::string& old_name, const std::string& new_name) {
    renames_.emplace_back(old_name, new_name);
  }
  // The option's current name for `name` (an old one's new name), or `name`.
  std::string current_name(const std::string& name) const {
    for (const auto& [old_name, new_name] : renames_)
      if (name == old_name) return new_name;
    return name;
  }
  // `args` with every old name (`--old` or `--old=value`) replaced by its new one, each said on
  // `notice`.
  std::vector<std::string> renamed(std::span<const std::string> args, std::ostream& notice) const {
    std::vector<std::string> out(args.begin(), args.end());
    for (std::string& arg : out) {
      const std::size_t eq = arg.find('=');
      const std::string name = arg.substr(0, eq);
      const std::string current = current_name(name);
      if (current == name) continue;
      notice << get_name() << ": " << name << " is deprecated, use " << current << '\n';
      arg = current + (eq == std::string::npos ? "" : arg.substr(eq));
    }
    return out;
  }

 private:
  std::vector<std::pair<std::string, std::string>> renames_;
};

// Why a parse ends the run: --help, or a usage error and its message (naming the option and
// the value).
struct Stop {
  bool help = false;
  std::string error;
};

// Parses `args` (without the program's name) into `app`, then runs `checks` (which throw
// CLI::ValidationError naming the option and the value); nullopt to go on.
inline std::optional<Stop> try_parse(CLI::App& app, std::span<const std::string> args,
                                     const std::function<void()>& checks = {}) {
  std::vector<std::string> given(args.begin(), args.end());
  if (const auto* ours = dynamic_cast<const App*>(&app)) given = ours->renamed(args, std::cerr);
  std::vector<std::string> reversed(given.rbegin(), given.rend());  // CLI11 takes them reversed
  try {
    app.parse(reversed);
    if (checks) checks();
  } catch (const CLI::CallForHelp&) {
    return Stop{true, {}};
  } catch (const CLI::RequiredError& e) {
    // CLI11 checks the required options before the extras: an unknown option is the first
    // thing to name (it may be the required one misspelt).
    const std::vector<std::string> rest = app.remaining();
    const auto unknown = std::ranges::find_if(
        rest, [](const std::string& arg) { return arg.starts_with("-") && arg.size() > 1; });
    if (unknown != rest.end()) return Stop{false, "unknown option '" + *unknown + "'"};
    return Stop{false, e.what()};
  } catch (const CLI::ExtrasError&) {
    // Named as the argv loops did (CLI11 2.1 lists all that is left, back to front).
    const std::string first = app.remaining().front();
    return Stop{false, (first.starts_with("-") ? "unknown option '" : "unexpected argument '") +
                           first + "'"};
  } catch (const CLI::Error& e) {
    return Stop{false, e.what()};
  }
  return std::nullopt;
}

// try_parse, and the exit status when the run is over already: --help (0, the help on `out`)
// or a usage error (2: "NAME: what" and the help on `err`).
inline std::optional<int> parse(CLI::App& app, std::span<const std::string> args, std::ostream& out,
                                std::ostream& err, const std::function<void()>& checks = {}) {
  const std::optional<Stop> stop = try_parse(app, args, checks);
  if (!stop) return std::nullopt;
  if (stop->help) {
    out << app.help();
    return kExitOk;
  }
  err << app.get_name() << ": " << stop->error << '\n' << app.help();
  return kExitUsage;
}

// The same for a program's main: its arguments after the name, help on stdout, errors on stderr.
inline std::optional<int> parse_main(CLI::App& app, int argc, char** argv,
                                     const std::function<void()>& checks = {}) {
  const std::vector<std::string> args(argv + std::min(argc, 1), argv + argc);
  return parse(app, args, std::cout, std::cerr, checks);
}

// The whole text as a finite number (strtod's forms). CLI11's own conversion takes "nan" and
// "inf", and its Range lets NaN through.
inline std::optional<double> finite_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// The whole text as a decimal whole number in [low, high]. CLI11's own conversion reads "010"
// as octal and "0x10" as hex, and "-1" as the largest unsigned number.
template <class Int = long long>
std::optional<Int> whole_number(const std::string& text, std::type_identity_t<Int> low,
                                std::type_identity_t<Int> high) {
  Int v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < low || v > high)
    return std::nullopt;
  return v;
}

// The shortest text that reads back as `v`.
inline std::string number_text(double v) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return std::string(text, ec == std::errc() ? end : text);
}

// A finite number for which `ok` holds; `what` says which ("a number > 0"), in the help and
// in the error: "--opt: 'x' is not a number > 0".
inline CLI::Validator number(
    const std::string& what, const std::function<bool(double)>& ok = [](double) { return true; }) {
  return CLI::Validator(
      [what, ok](std::string& text) -> std::string {
        const std::optional<double> v = finite_number(text);
        return v && ok(*v) ? std::string() : "'" + text + "' is not " + what;
      },
      what);
}

inline CLI::Validator finite() { return number("a finite number"); }
inline CLI::Validator positive() {
  return number("a number > 0", [](double v) { return v > 0; });
}
inline CLI::Validator non_negative() {
  return number("a number >= 0", [](double v) { return v >= 0; });
}
inline CLI::Validator number_in(double low, double high) {
  return number("a number in [" + number_text(low) + ", " + number_text(high) + "]",
                [low, high](double v) { return v >= low && v <= high; });
}

// A decimal whole number in [low, high]; the text is rewritten without leading zeros, so that
// CLI11 does not read it as octal (give it to Option::transform or add_checked, not ::check).
template <class Int = long long>
CLI::Validator whole_in(std::type_identity_t<Int> low, std::type_identity_t<Int> high) {
  const std::string what =
      "a whole number in [" + std::to_string(low) + ", " + std::to_string(high) + "]";
  return CLI::Validator(
      [what, low, high](std::string& text) -> std::string {
        const std::optional<Int> v = whole_number<Int>(text, low, high);
        if (!v) return "'" + text + "' is not " + what;
        text = std::to_string(*v);
        return {};
      },
      what);
}

// One of the given words: "--opt: 'x' is not one of a, b".
inline CLI::Validator one_of(std::initializer_list<std::string> words) {
  std::string list;
  for (const std::string& w : words) list += (list.empty() ? "" : ", ") + w;
  const std::vector<std::string> allowed(words);
  return CLI::Validator(
      [list, allowed](std::string& text) -> std::string {
        for (const std::string& w : allowed)
          if (text == w) return {};
        return "'" + text + "' is not one of " + list;
      },
      "one of " + list);
}

// An option shown as "NAME METAVAR" in --help, whose text `check` accepts (and may rewrite, as
// whole_in does) before CLI11 converts it into `value`. Option::check would hand the validator a
// copy of the text: a rewrite would be lost.
template <class T>
CLI::Option* add_checked(CLI::App& app, const std::string& name, T& value,
                         const std::string& metavar, const CLI::Validator& check,
                         const std::string& meaning) {
  return app.add_option(name, value, meaning)->option_text(metavar)->transform(check);
}

}  // namespace syncap::cli
