#!/usr/bin/env bash
# Lists every function in the library's sources (src/) longer than the limit
# (100 lines), by universal-ctags' start and end lines; exits 1 if there is
# one, 77 (skipped) without ctags.
#   scripts/check_function_length.sh [LIMIT] [DIR...]
set -euo pipefail
cd "$(dirname "$0")/.."
limit=${1:-100}
shift || true
dirs=("${@:-src}")
ctags_bin=$(command -v ctags-universal || command -v ctags || true)
if [ -z "$ctags_bin" ] || ! "$ctags_bin" --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "check_function_length: universal-ctags not found (apt-get install universal-ctags): skipped"
  exit 77
fi
long=$("$ctags_bin" -R --fields=+ne --c++-kinds=f --languages=C++ -o - "${dirs[@]}" |
  awk -F'\t' -v limit="$limit" '{
    start = ""; end = ""
    for (i = 4; i <= NF; i++) {
      if ($i ~ /^line:/) start = substr($i, 6)
      if ($i ~ /^end:/) end = substr($i, 5)
    }
    if (start != "" && end != "" && end - start + 1 > limit) print end - start + 1 " lines: " $2 ":" start " " $1
  }' | sort -rn)
if [ -n "$long" ]; then
  echo "functions over $limit lines:"
  echo "$long"
  exit 1
fi
echo "check_function_length: no function in ${dirs[*]} over $limit lines"
