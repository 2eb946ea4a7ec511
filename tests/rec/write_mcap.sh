#!/usr/bin/env bash
# Runs write_mcap.mjs with its npm packages, installed once into a cache
# (HBA_NPM_CACHE, default /tmp/hba-npm-mcap) under a lock. Exit 77 where
# node, npm or the registry is missing (the tests then skip).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache=${HBA_NPM_CACHE:-${TMPDIR:-/tmp}/hba-npm-mcap}
command -v node > /dev/null && command -v npm > /dev/null || { echo "SKIP: node or npm absent"; exit 77; }
mkdir -p "$cache"
(
  flock 9
  if [ ! -d "$cache/node_modules/@foxglove/rosmsg2-serialization" ] || [ ! -d "$cache/node_modules/lz4js" ]; then
    (cd "$cache" && timeout 300 npm install --silent --no-audit --no-fund --no-save @mcap/core@2 \
       @foxglove/rosmsg2-serialization@3 @foxglove/rosmsg@5 @foxglove/wasm-zstd@1 lz4js@0.2 > npm.log 2>&1) ||
      { echo "SKIP: npm could not install the MCAP writer"; cat "$cache/npm.log"; exit 77; }
  fi
) 9> "$cache/.lock"
# Put in place by a rename: tests run side by side, and a plain cp would
# truncate the script under another test's node while it reads it.
staged=$(mktemp "$cache/.write_mcap.XXXXXX")
cp "$here/write_mcap.mjs" "$staged"
mv -f "$staged" "$cache/write_mcap.mjs"
node "$cache/write_mcap.mjs" "$@"
