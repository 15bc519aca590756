#!/usr/bin/env bash
# The base image `debian:bookworm` made locally when no registry is reachable (../shared/NOTES-dependencies.md
# "Containers"): a minimal Debian 12 root file system by debootstrap from the host's Debian mirror, imported as the
# image the Dockerfile starts FROM. Nothing is done when the engine already has the image.
#   bash docker/base-image.sh            (DOCKER_HOST: the engine, see docker/engine.sh)
set -euo pipefail
die() { echo "base-image.sh: $*" >&2; exit 2; }
image=debian:bookworm
if docker image inspect "$image" > /dev/null 2>&1; then exit 0; fi
if docker pull -q "$image" > /dev/null 2>&1; then exit 0; fi  # a registry answered
command -v debootstrap > /dev/null || die "debootstrap not found: apt-get install debootstrap"
mirror=$(sed -n 's/^URIs: *\(http[^ ]*debian\)$/\1/p' /etc/apt/sources.list.d/*.sources 2> /dev/null | head -1)
[[ -n $mirror ]] || mirror=$(awk '$1 == "deb" && $3 == "bookworm" {print $2; exit}' /etc/apt/sources.list 2> /dev/null)
mirror=${mirror:-http://deb.debian.org/debian}
rootfs=$(mktemp -d /var/tmp/twinslam-rootfs.XXXX)
trap 'rm -rf "$rootfs"' EXIT
echo "base-image.sh: debootstrap bookworm from $mirror (about a minute)" >&2
debootstrap --variant=minbase bookworm "$rootfs" "$mirror" > "$rootfs.log" 2>&1 ||
  die "debootstrap failed: $rootfs.log"
rm -f "$rootfs.log"
tar -C "$rootfs" -c . | docker import - "$image" > /dev/null
echo "base-image.sh: imported $image" >&2
