#!/usr/bin/env bash
# scripts/arm64-sysroot.sh DIR
# Makes DIR an arm64 sysroot for cross-compiling syncap: Debian bookworm's arm64 -dev packages of
# every library syncap links (the arm64 twins of scripts/deps.sh's), extracted, not installed
# (mmdebstrap --variant=extract: no maintainer script runs, so no emulation is needed). The host's
# own packages are untouched: Debian's multiarch -dev packages do not install beside the amd64
# ones (libopencv-dev:arm64 would remove libopencv-dev). Idempotent: a sysroot made from the same
# package list is kept. Needs mmdebstrap (scripts/deps.sh cross) and the Debian mirror.
set -euo pipefail
dir=${1:?usage: scripts/arm64-sysroot.sh DIR}
mirror=${SYNCAP_DEBIAN_MIRROR:-http://deb.debian.org/debian}

PACKAGES=(
  # C and C++ runtime and headers of the target
  libc6-dev libstdc++-12-dev
  # acquisition, messaging, authentication, trigger GPIO
  libaravis-dev libusb-1.0-0-dev libv4l-dev liblcm-dev libsodium-dev libgpiod-dev libyaml-dev
  # vision and geometry, configuration, options (Ceres' SuiteSparse asks for BLAS and LAPACK)
  libopencv-dev libeigen3-dev libceres-dev libcgal-dev nlohmann-json3-dev libyaml-cpp-dev
  libcli11-dev libblas-dev liblapack-dev
  # tests and benchmarks, run under qemu-aarch64
  libcmocka-dev libgtest-dev libgmock-dev libbenchmark-dev
)
stamp="$dir/.syncap-sysroot"
want="bookworm arm64 ${PACKAGES[*]}"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
  echo "arm64-sysroot: $dir is up to date"
  exit 0
fi
rm -rf "$dir"
mkdir -p "$(dirname "$dir")"
include=$(IFS=,; echo "${PACKAGES[*]}")
echo "arm64-sysroot: extracting ${#PACKAGES[@]} packages and their dependencies into $dir"
mmdebstrap --quiet --variant=extract --arch=arm64 --skip=cleanup/apt/cache --include="$include" \
  bookworm "$dir" "$mirror"
# The libraries' shlibs files, the dependency information dpkg would hold on a board: the arm64
# packages' Depends come from them (dpkg-shlibdeps -L, cmake/SyncapCPackProject.cmake.in).
archives="$dir/var/cache/apt/archives"
: >"$dir/.syncap-shlibs"
for deb in "$archives"/*.deb; do
  dpkg-deb --ctrl-tarfile "$deb" | { tar -xO ./shlibs 2>/dev/null || true; } >>"$dir/.syncap-shlibs"
done
rm -f "$archives"/*.deb
# Absolute symbolic links (libz.so -> /lib/aarch64-linux-gnu/libz.so.1) would point into the
# build machine's root: make them relative, inside the sysroot.
find "$dir" -type l -lname '/*' -print0 | while IFS= read -r -d '' link; do
  target=$(readlink "$link")
  ln -sfn --relative "$dir$target" "$link"
done
# Some exported CMake targets (Ceres: its BLAS and LAPACK) name libraries by their absolute path
# on a board: point those into the sysroot (CMAKE_SYSROOT, set by the toolchain file).
grep -rl 'INTERFACE_LINK_LIBRARIES.*[";]/usr/lib/aarch64-linux-gnu/' \
  "$dir/usr/lib/aarch64-linux-gnu/cmake" --include='*[Tt]argets*.cmake' | while read -r file; do
  sed -i '/INTERFACE_LINK_LIBRARIES/ s#\([";]\)/usr/lib/aarch64-linux-gnu/#\1${CMAKE_SYSROOT}/usr/lib/aarch64-linux-gnu/#g' "$file"
done
# update-alternatives never ran: give the linker the reference BLAS and LAPACK that
# libopencv_core and Ceres were linked against (on a board, its alternatives choose).
lib="$dir/usr/lib/aarch64-linux-gnu"
for name in blas lapack; do
  for file in "lib$name.so.3" "lib$name.so"; do
    [ -e "$lib/$file" ] || ln -sfn "$name/$file" "$lib/$file"
  done
done
echo "$want" >"$stamp"
echo "arm64-sysroot: done ($(du -sh "$dir" | cut -f1))"
