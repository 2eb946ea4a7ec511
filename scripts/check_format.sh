#!/usr/bin/env bash
# Fails (exit 1) when a C++ file differs from what clang-format makes of it
# (.clang-format), listing the files. `scripts/check_format.sh --fix`
# rewrites them instead. The code is kept formatted alike by clang-format 14
# (Debian 12) and 19 (Debian 13): where they differ, the code is written so
# that they agree (a lambda named before the call that takes it, say).
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' 2>/dev/null || find apps bench examples fuzz include python src tests \( -name '*.[ch]pp' -o -name '*.h' \) | sort)
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
unformatted=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || unformatted+=("$f")
done
if [ "${#unformatted[@]}" -gt 0 ]; then
  echo "check_format: ${#unformatted[@]} file(s) not formatted by clang-format (.clang-format):" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  echo "check_format: run scripts/check_format.sh --fix" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted ($(clang-format --version | grep -o 'version [0-9.]*'))"
