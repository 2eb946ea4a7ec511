#!/usr/bin/env bash
# Configures and builds hba (Release) into ./build: every target, or only
# those named with --target (repeatable). Other arguments go to cmake's
# configure step (-DHBA_WERROR=ON, ...).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${HBA_JOBS:-$(nproc)}"
configure=()
targets=()
while [ "$#" -gt 0 ]; do
  case "$1" in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) configure+=("$1"); shift ;;
  esac
done
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${configure[@]}"
cmake --build build -j "$jobs" "${targets[@]}"
