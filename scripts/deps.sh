#!/usr/bin/env bash
# Installs exactly the Debian (bookworm) packages syncap needs to build, test and run.
# Idempotent: packages already present are skipped, and nothing is done when all are there.
# Uses sudo when not run as root.
#   scripts/deps.sh           what the native build and its tests need
#   scripts/deps.sh cross     ... and the arm64 cross toolchain, qemu and mmdebstrap
#                             (scripts/cross-build.sh, scripts/arm64-sysroot.sh)
#   scripts/deps.sh package   ... and what builds, checks and install-tests the Debian packages
#                             (scripts/package.sh)
set -euo pipefail

# One line per purpose, so a reader sees why each package is here.
PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config git clang-format ccache
  # acquisition: Aravis 0.8 (its pkg-config file requires libusb-1.0), V4L2 headers
  libaravis-dev libusb-1.0-0-dev aravis-tools-cli libv4l-dev
  # messaging: LCM library, lcm-gen, lcm-logger, lcm-logplayer
  liblcm-dev liblcm-bin
  # authenticated commands to the edges (crypto_auth, docs/design/security.md)
  libsodium-dev
  # trigger GPIO, and its YAML config (libyaml)
  libgpiod-dev gpiod libyaml-dev
  # vision and geometry (libopencv-dev brings libopencv-contrib-dev: aruco, for ChArUco boards)
  libopencv-dev libeigen3-dev libceres-dev libcgal-dev nlohmann-json3-dev libyaml-cpp-dev
  # anipose / Pose2Sim camera files (TOML: toml++)
  libtomlplusplus-dev
  # command-line options (CLI11)
  libcli11-dev
  # tests and benchmarks
  libcmocka-dev libgtest-dev libgmock-dev libbenchmark-dev
  # fuzzing the SDL parser (scripts/fuzz-sdl.sh): clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-14-dev
  # the venv of scripts/py-deps.sh (C3D readers that check the trajectory exports, the viewer)
  python3 python3-venv
  # private network namespaces (ip), unshare comes with util-linux
  iproute2 util-linux
  # fault injection (hil/run --fault): jq reads the groups and the log, libfaketime steps one
  # board's clock (clock-step)
  jq libfaketime
  # the web viewer's browser test (host.viewer.BrowserScreenshot): a browser on a virtual display
  chromium xvfb
)

for group in "$@"; do
  case "$group" in
    # arm64: the cross compilers, user-mode emulation (tests, instruction counts), the sysroot
    cross) PACKAGES+=(crossbuild-essential-arm64 qemu-user-static qemu-user mmdebstrap) ;;
    # Debian packages: dpkg-shlibdeps (dpkg-dev), the policy checker, a fresh root to install in
    package) PACKAGES+=(dpkg-dev fakeroot lintian mmdebstrap) ;;
    *) echo "deps: unknown group '$group' (cross, package)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${PACKAGES[@]}"; do
  # Captured, not piped into grep -q: under pipefail an early-exiting grep can fail the pipe.
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  if [ "$status" != "install ok installed" ]; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

echo "deps: installing ${#missing[@]} package(s): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "deps: done"
