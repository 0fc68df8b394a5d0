#!/usr/bin/env bash
# scripts/package.sh [arm64] [--host]
# Builds the Debian packages syncap-trigger, syncap-edge and syncap-host (amd64, from build/ or
# $SYNCAP_BUILD_DIR) or, with arm64, syncap-trigger and syncap-edge (and syncap-host with --host)
# cross-compiled in build-arm64/ (scripts/cross-build.sh), then checks each with lintian (an
# error fails). The packages install to /usr whatever the build's own install prefix; they land
# in <build>/packages. Install-test them with scripts/package-install-test.sh. docs/guide/deploy.md.
set -euo pipefail
cd "$(dirname "$0")/.."
arch=amd64
host_args=()
for arg in "$@"; do
  case "$arg" in
    arm64) arch=arm64 ;;
    --host) host_args=(--host) ;;
    *) echo "usage: scripts/package.sh [arm64] [--host]" >&2; exit 2 ;;
  esac
done
scripts/deps.sh package
start=$(date +%s)
if [ "$arch" = arm64 ]; then
  build_dir=${SYNCAP_CROSS_BUILD_DIR:-build-arm64}
  scripts/cross-build.sh arm64 "${host_args[@]}"
else
  build_dir=${SYNCAP_BUILD_DIR:-build}
  if [ ! -f "$build_dir/build.ninja" ]; then
    scripts/build.sh
  else
    cmake --build "$build_dir" --parallel "$(nproc)"
  fi
fi
rm -rf "$build_dir/packages"
cpack --config "$build_dir/CPackConfig.cmake" -B "$build_dir/packages"
rm -rf "$build_dir/packages/_CPack_Packages"
echo "package: built in $(( $(date +%s) - start )) s:"
status=0
for deb in "$build_dir"/packages/*.deb; do
  echo "  $(basename "$deb"): $(du -k "$deb" | cut -f1) KiB, installed $(dpkg-deb -f "$deb" Installed-Size) KiB"
  # Errors fail; warnings and notes are printed.
  lintian_status=0
  report=$(lintian --fail-on error "$deb" 2>&1) || lintian_status=$?
  grep -v 'running with root privileges' <<<"$report" || true
  if [ "$lintian_status" -ne 0 ]; then
    echo "package: lintian reports errors in $(basename "$deb")" >&2
    status=1
  fi
done
exit $status
