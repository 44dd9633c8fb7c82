#!/usr/bin/env bash
# Issue 39: builds the Debian package (CPack) and installs it on a clean Debian 12: a minimal
# bookworm made by debootstrap, in a chroot, where apt resolves the package's declared
# dependencies from the Debian mirror; then runs the default scene there from a folder of its own.
# Usage, as root with network to deb.debian.org: scripts/check-deb.sh [BUILD_DIR] [CHROOT_DIR]
# (defaults: build, /var/tmp/eggshell-deb12; an existing CHROOT_DIR is reused, never deleted).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
root=${2:-/var/tmp/eggshell-deb12}
scripts/build.sh
command -v debootstrap > /dev/null || apt-get install -y debootstrap
(cd "$build" && cpack -G DEB > cpack.log) || { cat "$build/cpack.log"; exit 1; }
deb=$(ls -t "$build"/eggshell_*.deb | head -1)
echo "check-deb: $deb"
dpkg-deb --field "$deb" Package Version Depends Recommends
if [ ! -x "$root/usr/bin/apt-get" ]; then
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian
fi
cp "$deb" "$root/tmp/"
mount -t proc proc "$root/proc"
trap 'umount "$root/proc"' EXIT
chroot "$root" apt-get update -qq
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --reinstall "/tmp/$(basename "$deb")"
chroot "$root" bash -c 'rm -rf /tmp/w && mkdir /tmp/w && cd /tmp/w && time egg run && ls out/great_court'
echo "check-deb: the package installs and runs the default scene on a clean Debian 12 ($root)"
