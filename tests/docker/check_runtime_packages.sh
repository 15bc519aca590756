#!/usr/bin/env bash
# check_runtime_packages.sh SCRIPT EXECUTABLE...: the packages SCRIPT derives from the executables include those an
# earlier hand-written list missed (OpenCV video for tracking, Draco and GeographicLib for tiles), name only installed
# packages, and a path that is not an executable is refused with exit 2 and one line naming it.
set -uo pipefail
script=$1; shift
fail() { echo "FAIL: $*" >&2; exit 1; }
packages=$(bash "$script" "$@") || fail "runtime-packages.sh exited $?"
for p in libfastrtps2.9 libopencv-video406 libdraco7 libgeographiclib23 libyaml-cpp0.7; do
  grep -qx "$p" <<< "$packages" || fail "$p not in: $(tr '\n' ' ' <<< "$packages")"
done
while read -r p; do
  dpkg-query -W -f='${Status}' "$p" 2> /dev/null | grep -q "install ok installed" || fail "$p is not an installed package"
done <<< "$packages"
err=$(bash "$script" /etc/hostname 2>&1 > /dev/null); code=$?
[[ $code -eq 2 ]] || fail "a non-executable gave exit $code, not 2"
[[ $(wc -l <<< "$err") -eq 1 && $err == *"/etc/hostname: not an ELF executable"* ]] || fail "unexpected message: $err"
echo "runtime packages ($(wc -l <<< "$packages")): $(tr '\n' ' ' <<< "$packages")"
