#include "syncap/proto/command_auth.hpp"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#include <fstream>
#include <sstream>

namespace syncap::proto {
namespace {

static_assert(CommandKey::kBytes == crypto_auth_KEYBYTES);
static_assert(std::tuple_size_v<CommandMac> == crypto_auth_BYTES);

void init_sodium() {
  // Thread-safe and idempotent; fails only without an entropy source.
  if (sodium_init() < 0) throw CommandKeyError("libsodium cannot initialise (no entropy source?)");
}

// |a - b| <= window, without overflow: a signed time far from now must not wrap into the window.
bool within(int64_t a, int64_t b, int64_t window) {
  int64_t difference = 0;
  if (__builtin_sub_overflow(a, b, &difference)) return false;
  return difference <= window && difference >= -window;
}

std::string to_hex(const CommandKey::Bytes& bytes) {
  std::string hex(2 * bytes.size() + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), bytes.data(), bytes.size());
  hex.pop_back();
  return hex;
}

std::string read_first_line(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CommandKeyError(path + ": cannot read the command key: " + std::strerror(errno));
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

CommandKey CommandKey::generate() {
  init_sodium();
  Bytes bytes;
  crypto_auth_keygen(bytes.data());
  return CommandKey(bytes);
}

CommandKey CommandKey::load(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    throw CommandKeyError(path + ": cannot read the command key: " + std::strerror(errno));
  if ((info.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    std::ostringstream mode;
    mode << std::oct << (info.st_mode & 0777);
    throw CommandKeyError(path + ": the command key is readable by others (mode " + mode.str() +
                          "); chmod 600 it and make the service user its owner");
  }
  const std::string line = read_first_line(path);
  Bytes bytes;
  std::size_t length = 0;
  const char* end = nullptr;
  if (line.size() != 2 * kBytes ||
      sodium_hex2bin(bytes.data(), bytes.size(), line.data(), line.size(), nullptr, &length,
                     &end) != 0 ||
      length != kBytes) {
    throw CommandKeyError(path + ": line 1: expected the command key as " +
                          std::to_string(2 * kBytes) + " hexadecimal digits (syncap keygen)");
  }
  return CommandKey(bytes);
}

void CommandKey::save(const std::string& path, bool replace) const {
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (replace ? O_TRUNC : O_EXCL);
  const int fd = ::open(path.c_str(), flags, 0600);
  if (fd < 0) {
    throw CommandKeyError(path + ": cannot write the command key: " + std::strerror(errno) +
                          (errno == EEXIST ? " (replace it with --force)" : ""));
  }
  // An existing file keeps its mode under O_TRUNC: make it the owner's alone first.
  const std::string text = to_hex(bytes_) + "\n";
  const bool written = ::fchmod(fd, 0600) == 0 &&
                       ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int write_errno = errno;
  if (::close(fd) != 0 || !written) {
    throw CommandKeyError(
        path + ": cannot write the command key: " + std::strerror(written ? errno : write_errno));
  }
}

CommandMac mac_of_encoding(const std::vector<uint8_t>& encoding, const CommandKey& key) {
  CommandMac mac;
  crypto_auth(mac.data(), encoding.data(), encoding.size(), key.bytes().data());
  return mac;
}

bool same_mac(const CommandMac& a, const int8_t (&field)[32]) {
  return sodium_memcmp(a.data(), field, a.size()) == 0;
}

int64_t new_sender_id() {
  init_sodium();
  int64_t id = 0;
  while (id == 0) randombytes_buf(&id, sizeof id);
  return id;
}

const char* describe(CommandCheck check) {
  switch (check) {
    case CommandCheck::kAccepted:
      return "accepted";
    case CommandCheck::kNoKey:
      return "refused: this edge has no command key (--command-key), it obeys no command";
    case CommandCheck::kBadMac:
      return "refused: not signed with this installation's key";
    case CommandCheck::kOutsideWindow:
      return "refused: sent outside the time window (clocks apart, or an old command)";
    case CommandCheck::kReplayed:
      return "refused: replayed (sequence not above the sender's last)";
    case CommandCheck::kBeforeStart:
      return "refused: sent before this edge started (a replay, or clocks apart)";
  }
  return "refused: unknown reason";
}

CommandGuard::CommandGuard(std::optional<CommandKey> key, int64_t window_ns,
                           int64_t created_realtime_ns)
    : key_(std::move(key)), window_ns_(window_ns), created_ns_(created_realtime_ns) {}

CommandCheck CommandGuard::check_authentic(int64_t sender, int64_t sequence, int64_t sent_ns,
                                           int64_t now_ns) {
  if (!within(now_ns, sent_ns, window_ns_)) return CommandCheck::kOutsideWindow;
  if (sent_ns < created_ns_) return CommandCheck::kBeforeStart;
  forget_stale(now_ns);
  const auto last = last_.find(sender);
  if (last != last_.end() && sequence <= last->second.sequence) return CommandCheck::kReplayed;
  // The newest send time of the sender's accepted messages: once it leaves the window, every
  // message of that sender fails the window check, whatever its sender's clock did.
  const int64_t newest = last == last_.end() ? sent_ns : std::max(sent_ns, last->second.sent_ns);
  last_[sender] = {sequence, newest};
  return CommandCheck::kAccepted;
}

void CommandGuard::forget_stale(int64_t now_ns) {
  std::erase_if(
      last_, [&](const auto& entry) { return !within(now_ns, entry.second.sent_ns, window_ns_); });
}

}  // namespace syncap::proto
