#!/usr/bin/env bash
# Quick start 1: install what is missing, build, run the main job on the default scene.
# egg's exit code 1 is a result (the report says which patch or simulation failed and why) and the
# demo still completes; 2 (bad input) or anything else is an error of the demo itself.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
BUILD_DIR=${EGG_BUILD_DIR:-build}
OUT=${EGG_OUT:-out/great_court}
status=0
"$BUILD_DIR/bin/egg" run samples/great_court.json --out "$OUT" || status=$?
case "$status" in
  0) echo "demo: results in $OUT (report.json, plan.svg, cut/, supports/, bom.csv)" ;;
  1) echo "demo: results in $OUT; the run reports failures (exit 1): see \"failures\" in $OUT/report.json" ;;
  *) echo "demo: egg run failed with exit code $status" >&2; exit "$status" ;;
esac
