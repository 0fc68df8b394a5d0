#!/usr/bin/env bash
# Formats every C/C++ source the project tracks (or is about to track) in place with clang-format.
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files --cached --others --exclude-standard '*.c' '*.h' '*.cpp' '*.hpp' |
  xargs -r clang-format -i
