#include "drop_policy.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace syncap::fakecam {
namespace {

// SplitMix64's finaliser: a well-mixed 64-bit hash.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::uint64_t parse_frame(std::string_view text) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    throw std::invalid_argument("'" + std::string(text) + "' is not a frame number");
  }
  return value;
}

double parse_rate(std::string_view text) {
  const bool percent = text.ends_with('%');
  if (percent) text.remove_suffix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value)) {
    throw std::invalid_argument("not a rate (use 0.05 or 5%)");
  }
  if (percent) value /= 100.0;
  if (value < 0.0 || value > 1.0) throw std::invalid_argument("a rate must be 0 to 1 (0% to 100%)");
  return value;
}

}  // namespace

DropPolicy DropPolicy::parse(std::string_view text, std::uint64_t seed) {
  DropPolicy policy;
  policy.text_ = std::string(text);
  policy.seed_ = seed;
  if (text.find_first_of(".%") != std::string_view::npos) {
    policy.rate_ = parse_rate(text);
    return policy;
  }
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    const std::size_t dash = item.find('-');
    const std::uint64_t first = parse_frame(item.substr(0, dash));
    const std::uint64_t last =
        dash == std::string_view::npos ? first : parse_frame(item.substr(dash + 1));
    if (last < first)
      throw std::invalid_argument("range '" + std::string(item) + "' runs backwards");
    policy.ranges_.push_back({first, last});
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
    if (text.empty()) throw std::invalid_argument("the list ends with ','");
  }
  if (policy.ranges_.empty()) throw std::invalid_argument("empty list");
  return policy;
}

bool DropPolicy::drops(std::uint64_t frame) const {
  for (const Range& range : ranges_) {
    if (frame >= range.first && frame <= range.last) return true;
  }
  if (rate_ <= 0.0) return false;
  // The top 53 bits as a uniform double in [0, 1).
  const double u = static_cast<double>(mix(seed_ ^ mix(frame)) >> 11) * 0x1.0p-53;
  return u < rate_;
}

std::string DropPolicy::describe() const {
  if (rate_ > 0.0) return text_ + " of frames (seed " + std::to_string(seed_) + ")";
  if (!ranges_.empty()) return "frames " + text_;
  return "nothing";
}

}  // namespace syncap::fakecam
