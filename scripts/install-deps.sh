#!/usr/bin/env bash
# Installs the Debian packages eggshell needs, only those missing (idempotent).
# Usage: scripts/install-deps.sh   (as root, or with sudo available)
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config ccache
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libopenmesh-dev libceres-dev libsuitesparse-dev libgoogle-glog-dev libgflags-dev
  libnlopt-cxx-dev libnlopt-dev libassimp-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev
  libcairo2-dev libdxflib-dev
  libhersheyfont-dev hershey-fonts-data libzip-dev   # fabrication: single-stroke labels, cut.zip (issue 38)
  librsvg2-dev               # pipeline/svg_png.cpp: PNG previews of report.html's figures
  python3-ezdxf librsvg2-bin poppler-utils admesh
  librecad                   # test_dxf_writer: LibreCAD's own print (dxf2pdf) of a sheet DXF (issue 38)
  python3-jsonschema         # test_scene_schema: the scene schema checked by an independent validator (issue 39)
  parallel                   # egg sweep: jobs.txt on one machine (issue 18, test_sweep)
  clang libclang-rt-14-dev   # scripts/fuzz.sh: libFuzzer targets (issue 17)
  clang-format clang-tidy    # .clang-format (checked by the Format test), .clang-tidy (identifier naming)
  chromium                   # test_report_html: report.html rendered headless (skipped without it)
  calculix-ccx               # verification/: the FE check of the deployed grid (issue 37)
  libtinygltf-dev            # export/glb_writer.cpp: model.glb (issue 38)
  nodejs                     # export/js: model.3dm (rhino3dm) and the GLB/3dm checks (issue 38)
)
# npm for export/js's packages: Debian's package only where no npm came with Node.js already.
command -v npm >/dev/null || PACKAGES+=(npm)

# The npm packages of export/js (rhino3dm, gltf-validator; three and esbuild bundle the 3D view at build time), exactly as its package-lock.json pins
# them; only when node_modules is missing or older than the lockfile.
install_npm_packages() {
  local js
  js="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/export/js"
  [ -f "$js/package-lock.json" ] || return 0
  if [ -f "$js/node_modules/.package-lock.json" ] &&
     [ "$js/node_modules/.package-lock.json" -nt "$js/package-lock.json" ]; then
    echo "install-deps: npm packages of export/js present"
    return 0
  fi
  command -v npm >/dev/null || { echo "install-deps: npm is missing (Debian package npm)" >&2; return 1; }
  echo "install-deps: npm ci in $js"
  (cd "$js" && npm ci --no-audit --no-fund)
}

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  install_npm_packages
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
install_npm_packages
