#!/usr/bin/env bash
# Installs missing Debian packages, configures and builds eggshell (Release) into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
BUILD_DIR=${EGG_BUILD_DIR:-build}
JOBS=${EGG_JOBS:-$(nproc)}
# EGG_UNITY=1 (set by .ci/run): a unity build, up to 16 sources of a target per translation unit,
# about half the CPU of a cold build (docs/measurements.md, "CI build time"). Developers build per
# file, so a missing include that a unity neighbour would hide still shows.
UNITY=()
if [ "${EGG_UNITY:-0}" = 1 ]; then
  UNITY=(-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16)
fi
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "${UNITY[@]}"
fi
cmake --build "$BUILD_DIR" -j "$JOBS"
