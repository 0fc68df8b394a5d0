#!/usr/bin/env bash
# Checks that every C/C++ source the project tracks (or is about to track) is clang-formatted.
# Prints the offending files and exits 1 when any is not; scripts/format.sh fixes them.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files --cached --others --exclude-standard \
  '*.c' '*.h' '*.cpp' '*.hpp' 2>/dev/null || find . -name '*.[ch]' -o -name '*.[ch]pp')
[ ${#files[@]} -gt 0 ] || { echo "format-check: no sources"; exit 0; }
bad=()
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then bad+=("$f"); fi
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "format-check: ${#bad[@]} file(s) not clang-formatted (run scripts/format.sh):"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "format-check: ${#files[@]} files clang-formatted"
