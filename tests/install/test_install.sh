#!/usr/bin/env bash
# Issue 39: `cmake --install` into a temporary prefix gives a working egg: from a folder outside the
# source tree it runs the default scene (found under PREFIX/share/eggshell), writes model.3dm with
# the installed rhino3dm, and `egg init` names the installed schema.
# Usage: test_install.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "test_install: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log" || { cat "$tmp/install.log"; fail "cmake --install failed"; }
share="$tmp/prefix/share/eggshell"
for f in bin/egg share/eggshell/samples/great_court.json share/eggshell/samples/scenes/bump_patch.json \
         share/eggshell/docs/scene.schema.json share/eggshell/docs/scene-reference.md \
         share/eggshell/export/js/write3dm.mjs share/eggshell/README.md; do
  [ -e "$tmp/prefix/$f" ] || fail "$f is not installed"
done
[ -f "$share/export/js/node_modules/rhino3dm/rhino3dm.js" ] || fail "rhino3dm is not installed"
[ ! -e "$share/export/js/node_modules/gltf-validator" ] || fail "gltf-validator (a test tool) is installed"

mkdir "$tmp/elsewhere"
cd "$tmp/elsewhere"
# The installed tree's own export/js, not the source tree's the build was configured with.
EGG_EXPORT_JS="$share/export/js" "$tmp/prefix/bin/egg" run -q --out "$tmp/elsewhere/gc" > run.log 2>&1 ||
  { cat run.log; fail "egg run (the default scene) from another folder failed"; }
grep -q '"name": "great_court"' gc/report.json || fail "the default scene was not the Great Court"
for f in report.html cut.zip deployed.json model.glb; do [ -s "gc/$f" ] || fail "gc/$f is missing"; done
if command -v node > /dev/null; then [ -s gc/model.3dm ] || fail "gc/model.3dm is missing"; fi

"$tmp/prefix/bin/egg" init bump --out bump.json 2> init.log || { cat init.log; fail "egg init failed"; }
# Named relative to the scene (both under one top folder here) or absolute: either way the file.
schema=$(sed -n 's/^  "\$schema": "\(.*\)",$/\1/p' bump.json)
[ "$(realpath -e "$schema" 2> /dev/null)" = "$(realpath "$share/docs/scene.schema.json")" ] ||
  fail "egg init does not name the installed schema: $schema"
echo "test_install: ok ($(du -sh "$tmp/prefix" | cut -f1) installed)"
