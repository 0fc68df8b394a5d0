// syncap-fakecam: serves a directory of rendered 8-bit images as a GigE Vision camera on a
// loopback address inside hil/netns-run, one frame per trigger. See docs/design/fakecam.md.
#include <csignal>
#include <cstdio>
#include <ctime>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "fake_camera.hpp"
#include "image_set.hpp"
#include "options.hpp"
#include "server.hpp"

namespace {

using namespace syncap::fakecam;

enum ExitStatus { kOk = 0, kFailure = 1, kUsage = 2 };

constexpr std::size_t kBytesPerMb = 1024 * 1024;

// SIGINT and SIGTERM are blocked in every thread (Aravis' included, so it must happen first) and
// taken by the main thread with sigtimedwait, so a stop always finds the threads in a clean state.
sigset_t block_stop_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  return signals;
}

// Waits for SIGINT/SIGTERM or a failure of the server; the failure, if that ended the wait.
std::optional<std::string> wait_for_stop(const sigset_t& signals, const Server& server) {
  const timespec slice{0, 100'000'000};
  for (;;) {
    if (sigtimedwait(&signals, nullptr, &slice) > 0) return std::nullopt;
    if (auto failure = server.failure()) return failure;
  }
}

void print_start(const Options& options, const ImageSet& images) {
  std::printf(
      "syncap-fakecam: serving %zu images %dx%d (frames %llu-%llu) from %s on %s as %s, trigger "
      "%s, first frame %llu, drop %s, delay %lld ms%s\n",
      images.size(), images.width(), images.height(),
      static_cast<unsigned long long>(images.first_frame()),
      static_cast<unsigned long long>(images.last_frame()), images.directory().c_str(),
      options.address.c_str(), options.serial.c_str(), options.trigger.describe().c_str(),
      static_cast<unsigned long long>(options.start_frame), options.drop.describe().c_str(),
      static_cast<long long>(options.delay_ms), options.loop ? ", looping" : "");
  std::fflush(stdout);
}

void print_summary(const ServerStats& s) {
  std::printf(
      "syncap-fakecam: triggers=%llu sent=%llu dropped=%llu idle=%llu no_image=%llu missed=%llu "
      "errors=%llu\n",
      static_cast<unsigned long long>(s.triggers), static_cast<unsigned long long>(s.sent),
      static_cast<unsigned long long>(s.dropped), static_cast<unsigned long long>(s.idle),
      static_cast<unsigned long long>(s.no_image), static_cast<unsigned long long>(s.missed),
      static_cast<unsigned long long>(s.errors));
  std::fflush(stdout);
}

int serve(const Options& options, const sigset_t& signals) {
  const ImageSet images = ImageSet::load(options.images, options.cache_mb * kBytesPerMb);
  FakeCamera camera(options.address, options.serial, images.width(), images.height(),
                    options.trigger.kind, options.link_mbps);
  Server server(options, images, camera);
  server.start();
  if (!options.quiet) print_start(options, images);
  const auto failure = wait_for_stop(signals, server);
  server.stop();
  if (!options.quiet) print_summary(server.stats());
  if (!failure) return kOk;
  std::fprintf(stderr, "syncap-fakecam: %s\n", failure->c_str());
  return kFailure;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<const char*> arguments(argv + 1, argv + argc);
  const ParsedOptions parsed = parse_options(arguments);
  if (parsed.result == ParsedOptions::Result::help) {
    std::fputs(usage().c_str(), stdout);
    return kOk;
  }
  if (parsed.result == ParsedOptions::Result::invalid) {
    std::fprintf(stderr, "syncap-fakecam: %s\n%s", parsed.error.c_str(), usage().c_str());
    return kUsage;
  }
  const sigset_t signals = block_stop_signals();
  try {
    return serve(parsed.options, signals);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "syncap-fakecam: %s\n", error.what());
    return kFailure;
  }
}
