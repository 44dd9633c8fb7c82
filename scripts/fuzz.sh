#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (build-fuzz/, -DEGG_FUZZ=ON) and runs each for
# EGG_FUZZ_RUNS inputs (default 10000), starting from tests/fuzz/corpus/<target>/ (issue 17).
# New inputs go to build-fuzz/corpus/<target>/, crashes to build-fuzz/crashes/<target>/.
# Usage: scripts/fuzz.sh [target ...]   (targets: scene sweep cli obj stl ply off gltf glb)
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang++ >/dev/null || { echo "fuzz: needs clang (apt-get install -y clang)" >&2; exit 1; }
BUILD_DIR=${EGG_FUZZ_BUILD_DIR:-build-fuzz}
RUNS=${EGG_FUZZ_RUNS:-10000}
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(scene sweep cli obj stl ply off gltf glb)
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  CXX=clang++ cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DEGG_FUZZ=ON -DEGG_BUILD_TESTS=OFF
fi
cmake --build "$BUILD_DIR" -j "${EGG_JOBS:-$(nproc)}" --target $(printf 'fuzz_%s ' "${TARGETS[@]}")
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
for t in "${TARGETS[@]}"; do
  mkdir -p "$BUILD_DIR/corpus/$t" "$BUILD_DIR/crashes/$t"
  echo "== fuzz_$t: $RUNS inputs"
  dict=()
  [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
  "$BUILD_DIR/fuzz_$t" "${dict[@]}" -runs="$RUNS" -max_len=65536 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$BUILD_DIR/crashes/$t/" "$BUILD_DIR/corpus/$t" "tests/fuzz/corpus/$t" 2>&1 | \
    grep -E "^(#[0-9]+ +DONE|Done|stat::number_of_executed_units|stat::peak_rss_mb|==[0-9]+==ERROR|SUMMARY|artifact_prefix)" || true
  crashes=$(find "$BUILD_DIR/crashes/$t" -type f | wc -l)
  echo "fuzz_$t: crashes/timeouts/leaks saved: $crashes"
done
