#!/usr/bin/env bash
# Quick start 2: install what is missing, build, run the whole test suite (CTest + GoogleTest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
BUILD_DIR=${EGG_BUILD_DIR:-build}
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "${EGG_JOBS:-$(nproc)}" --timeout 1200
