#!/usr/bin/env bash
# scripts/package-install-test.sh [PACKAGE_DIR]
# Installs the amd64 packages of PACKAGE_DIR (default build/packages, made by scripts/package.sh)
# with dpkg -i into a fresh Debian bookworm root and runs what was installed there:
#   1. the root: mmdebstrap --variant=minbase plus exactly the packages' Depends (from the
#      archive), made in a temporary folder and thrown away at the end;
#   2. dpkg -i of every syncap package: the maintainer scripts make the user syncap (groups gpio,
#      video) and enable nothing;
#   3. syncap-edge --help, syncap-trigger --help, syncap --help, syncap-host --help;
#   4. a replay run of the installed syncap-edge on 6 frames with bright discs, paced by the
#      installed syncap-trigger (simulated chip) over LCM multicast in a private network
#      namespace, recorded by the installed syncap record and read back with syncap log: 6 blob
#      frames of 3 blobs each at the discs' centres;
#   5. the installed units and conffiles where the docs say (docs/guide/deploy.md).
# Ends with "package-install-test: passed". Needs root (chroot; without it: exit 77, which ctest
# counts as skipped) and the Debian mirror; ctest runs it with the label package.
# $SYNCAP_DEBIAN_MIRROR overrides the mirror.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=$(cd "${1:-${SYNCAP_BUILD_DIR:-build}/packages}" && pwd)
mirror=${SYNCAP_DEBIAN_MIRROR:-http://deb.debian.org/debian}
fail() { echo "package-install-test: FAILED: $*" >&2; exit 1; }
step() { echo "package-install-test: $*"; }

shopt -s nullglob
debs=("$packages"/syncap-*_amd64.deb)
for name in syncap-trigger syncap-edge syncap-host; do
  found=("$packages/${name}_"*_amd64.deb)
  [ ${#found[@]} -gt 0 ] ||
    fail "no ${name}_*_amd64.deb in $packages (run scripts/package.sh): the test runs all three"
done
if [ "$(id -u)" -ne 0 ]; then
  echo "package-install-test: skipped: needs root (chroot, dpkg -i into the root)"
  exit 77  # ctest: skipped
fi
command -v mmdebstrap >/dev/null || scripts/deps.sh package

root=$(mktemp -d /tmp/syncap-install-test.XXXXXX)
trap 'rm -rf "$root"' EXIT
start=$(date +%s)

# 1. The packages' dependencies by name (versions are the archive's, which satisfy them).
depends=$(for deb in "${debs[@]}"; do dpkg-deb -f "$deb" Depends; done |
  tr ',' '\n' | sed -e 's/(.*)//' -e 's/|.*//' -e 's/ //g' | sort -u | grep -v '^$' | paste -sd,)
step "a fresh bookworm root in $root with: $depends"
mmdebstrap --quiet --variant=minbase --include="$depends" bookworm "$root" "$mirror" ||
  fail "mmdebstrap could not make the root"

# 2. dpkg -i, as on a board.
mkdir -p "$root/tmp/debs"
cp "${debs[@]}" "$root/tmp/debs/"
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root "$@"; }
in_root sh -c 'dpkg -i /tmp/debs/*.deb' || fail "dpkg -i failed"
for deb in "${debs[@]}"; do
  name=$(dpkg-deb -f "$deb" Package)
  [ "$(in_root dpkg-query -W -f='${Status}' "$name")" = "install ok installed" ] ||
    fail "$name is not installed"
done
groups=$(in_root id -nG syncap) || fail "no user syncap"
step "user syncap, groups: $groups"
for deb in "${debs[@]}"; do
  case "$(dpkg-deb -f "$deb" Package)" in
    syncap-trigger) [[ " $groups " == *" gpio "* ]] || fail "syncap is not in gpio" ;;
    syncap-edge) [[ " $groups " == *" video "* ]] || fail "syncap is not in video" ;;
  esac
done
enabled=$(find "$root/etc/systemd/system" -path '*.wants/syncap*' 2>/dev/null || true)
[ -z "$enabled" ] || fail "the installation enabled units: $enabled"

# 3. The installed programs start and know their options.
for program in syncap-edge syncap-trigger syncap syncap-host; do
  in_root "$program" --help >"$root/tmp/help.txt" 2>&1 || fail "$program --help failed"
  grep -qi "usage" "$root/tmp/help.txt" || fail "$program --help printed no usage"
  step "$program --help: $(head -1 "$root/tmp/help.txt")"
done

# 4. A replay run of the installed edge: 6 frames, 3 discs each, paced by the installed trigger.
python3 - "$root/tmp/frames" <<'PY'
import os, sys
out = sys.argv[1]
os.makedirs(out)
width, height = 320, 240
for f in range(6):
    centres = [(60 + 4 * f, 50), (160, 120 + 3 * f), (250, 190)]
    pixels = bytearray([20]) * (width * height)
    for cx, cy in centres:
        for y in range(cy - 6, cy + 7):
            for x in range(cx - 6, cx + 7):
                if (x - cx) ** 2 + (y - cy) ** 2 <= 25:
                    pixels[y * width + x] = 240
    with open(os.path.join(out, "frame_%04d.pgm" % f), "wb") as file:
        file.write(b"P5 %d %d 255\n" % (width, height) + bytes(pixels))
PY
# As on a network of boards: the installed trigger (its in-process simulated chip) paces the
# installed edge over LCM multicast, syncap record keeps what the edge sends; all of it in a
# private network namespace (multicast never leaves it) and inside the root.
cat >"$root/tmp/replay.sh" <<'SH'
#!/bin/sh
set -e
url='udpm://239.255.76.67:7667?ttl=0'
syncap record --out /tmp/edge.lcm --lcm-url "$url" 2>/tmp/record.err &
record=$!
syncap-edge --source replay:/tmp/frames --camera-id 4 --mode blobs --threshold-dn 128 \
  --lcm-url "$url" --exit-after-last --quiet &
edge=$!
syncap-trigger --chip sim --rate-hz 10 --count 6 --start-delay-ms 1000 --lcm-url "$url" --quiet
wait $edge
sleep 0.5
kill -INT $record
wait $record || true
SH
timeout 120 unshare -n sh -c 'ip link set lo up && ip route add 239.0.0.0/8 dev lo &&
  exec chroot "$0" /usr/bin/env -i PATH=/usr/bin:/bin sh /tmp/replay.sh' "$root" ||
  fail "the replay run of the installed trigger, edge and recorder failed"
in_root syncap log /tmp/edge.lcm >"$root/tmp/edge.jsonl" || fail "syncap log failed"
python3 - "$root/tmp/edge.jsonl" <<'PY' || fail "the replayed messages are wrong"
import json, sys
frames = [e for e in map(json.loads, open(sys.argv[1])) if e.get("type", "").endswith("blob_frame_t")]
assert len(frames) == 6, f"{len(frames)} blob frames, expected 6"
for f, event in enumerate(frames):
    message = event["fields"]
    assert message["camera_id"] == 4, message
    blobs = sorted((round(b["x"], 1), round(b["y"], 1)) for b in message["blobs"])
    want = sorted([(60 + 4 * f, 50), (160, 120 + 3 * f), (250, 190)])
    assert blobs == [(float(x), float(y)) for x, y in want], (f, blobs, want)
print("package-install-test: 6 blob frames of 3 blobs at the discs' centres")
PY

# 5. Units, conffiles and docs where docs/guide/deploy.md says.
for deb in "${debs[@]}"; do
  case "$(dpkg-deb -f "$deb" Package)" in
    syncap-trigger) expect=(usr/lib/systemd/system/syncap-trigger.service
                            etc/syncap/trigger.conf.example usr/lib/udev/rules.d/60-syncap-gpio.rules) ;;
    syncap-edge) expect=(usr/lib/systemd/system/syncap-edge@.service etc/syncap/edge.yaml.example) ;;
    *) expect=() ;;
  esac
  for file in "${expect[@]}" "usr/share/doc/$(dpkg-deb -f "$deb" Package)/copyright"; do
    [ -e "$root/$file" ] || fail "/$file is missing"
  done
done
grep -q '^ExecStart=/usr/bin/syncap-edge ' "$root/usr/lib/systemd/system/syncap-edge@.service" ||
  fail "syncap-edge@.service does not run /usr/bin/syncap-edge"
step "passed in $(( $(date +%s) - start )) s"
