// Who may command the edges (docs/design/security.md). LCM names no sender and anyone on the
// segment can publish, so the messages that change an edge (edge_command_t, clip_polygon_t) carry a
// MAC under a key the installation shares: libsodium's crypto_auth (HMAC-SHA-512-256) over the
// message's LCM encoding with the mac field zeroed, so every field, present and future, is covered.
// A sender id, a per-sender sequence and the send time stop a captured command from being replayed.
// Data messages (triggers, blobs, silhouettes, status) stay unauthenticated and are validated.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>
#include "syncap/proto/clock.hpp"

namespace syncap::proto {

// A key file that is missing, malformed, or readable by others; the message names the file.
class CommandKeyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The installation's 32-byte secret. On disk: 64 hexadecimal digits and a newline, in a file its
// owner alone may read (mode 0600 or 0400), like an ssh private key.
class CommandKey {
 public:
  static constexpr std::size_t kBytes = 32;
  using Bytes = std::array<unsigned char, kBytes>;

  explicit CommandKey(const Bytes& bytes) : bytes_(bytes) {}
  // A new random key (libsodium's randombytes).
  static CommandKey generate();
  // Throws CommandKeyError: no such file, group or others may read it, not 64 hex digits.
  static CommandKey load(const std::string& path);
  // Creates the file with mode 0600; refuses an existing one unless `replace` (CommandKeyError).
  void save(const std::string& path, bool replace) const;

  const Bytes& bytes() const { return bytes_; }

 private:
  Bytes bytes_;
};

using CommandMac = std::array<unsigned char, 32>;

// The MAC of an encoded message (whose mac field is zeroed).
CommandMac mac_of_encoding(const std::vector<uint8_t>& encoding, const CommandKey& key);
// Constant-time comparison (sodium_memcmp).
bool same_mac(const CommandMac& a, const int8_t (&field)[32]);
// A random non-zero id for this sending process.
int64_t new_sender_id();

// The message's LCM encoding with its mac field zeroed: what the MAC covers.
template <class Message>
std::vector<uint8_t> encoding_without_mac(Message message) {
  std::fill(std::begin(message.mac), std::end(message.mac), int8_t{0});
  std::vector<uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

template <class Message>
bool mac_valid(const Message& message, const CommandKey& key) {
  return same_mac(mac_of_encoding(encoding_without_mac(message), key), message.mac);
}

// Signs the messages of one sending process: its id, the next sequence, the time, the MAC.
class CommandSigner {
 public:
  explicit CommandSigner(CommandKey key) : key_(std::move(key)), sender_(new_sender_id()) {}

  template <class Message>
  void sign(Message& message) {
    message.sender = sender_;
    message.sequence = ++sequence_;
    message.sent_realtime_ns = realtime_now_ns();
    const CommandMac mac = mac_of_encoding(encoding_without_mac(message), key_);
    std::memcpy(message.mac, mac.data(), mac.size());
  }

  int64_t sender() const { return sender_; }
  int64_t last_sequence() const { return sequence_; }

 private:
  CommandKey key_;
  int64_t sender_;
  int64_t sequence_ = 0;
};

// What the receiver makes of a signed message; the values are camera_status_t's COMMAND_*.
enum class CommandCheck : int8_t {
  kAccepted = 0,
  kNoKey = 1,
  kBadMac = 2,
  kOutsideWindow = 3,
  kReplayed = 4,
  kBeforeStart = 5,
};

// "refused: not signed with this installation's key", for logs and heartbeats.
const char* describe(CommandCheck check);

// Accepts a signed message at most once: its MAC is the key's, it was sent within `window_ns` of
// the receiver's clock, not before the guard was created (a command captured earlier cannot be
// replayed after the receiver restarts), and its sequence is above the last one accepted from its
// sender. Without a key nothing is accepted. State changes only for authentic messages, so a
// flood of forgeries costs a MAC each and no memory.
class CommandGuard {
 public:
  CommandGuard(std::optional<CommandKey> key, int64_t window_ns, int64_t created_realtime_ns);

  template <class Message>
  CommandCheck check(const Message& message, int64_t now_realtime_ns) {
    if (!key_) return CommandCheck::kNoKey;
    if (!mac_valid(message, *key_)) return CommandCheck::kBadMac;
    return check_authentic(message.sender, message.sequence, message.sent_realtime_ns,
                           now_realtime_ns);
  }

  bool has_key() const { return key_.has_value(); }
  std::size_t senders_remembered() const { return last_.size(); }

 private:
  struct LastAccepted {
    int64_t sequence;  // the sender's last accepted
    int64_t sent_ns;   // the newest send time among its accepted messages
  };
  CommandCheck check_authentic(int64_t sender, int64_t sequence, int64_t sent_ns, int64_t now_ns);
  // Senders whose last message is older than the window: any replay of theirs fails the window.
  void forget_stale(int64_t now_ns);

  std::optional<CommandKey> key_;
  int64_t window_ns_;
  int64_t created_ns_;
  std::map<int64_t, LastAccepted> last_;
};

}  // namespace syncap::proto
