#!/usr/bin/env bash
# Quick start 1: install what is missing, build, run the main job on the default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
BUILD_DIR=${EGG_BUILD_DIR:-build}
OUT=${EGG_OUT:-out/great_court}
"$BUILD_DIR/bin/egg" run samples/great_court.json --out "$OUT"
echo "demo: results in $OUT (report.json)"
