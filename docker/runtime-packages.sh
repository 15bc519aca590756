#!/usr/bin/env bash
# The Debian packages that hold the shared libraries these executables link, one per line (for the image's runtime
# stage: exactly what the binaries need, found from the binaries, not listed by hand). Exit 2 naming a library that
# no package holds or that the loader cannot find.
#   bash docker/runtime-packages.sh EXECUTABLE...
set -euo pipefail
die() { echo "runtime-packages.sh: $*" >&2; exit 2; }
[[ $# -ge 1 ]] || die "usage: runtime-packages.sh EXECUTABLE..."
# The libraries each executable names itself (DT_NEEDED), located where the loader finds them; apt-get brings what
# those libraries need in turn.
libs=$(for exe in "$@"; do
  [[ -f $exe && -x $exe ]] && readelf -h "$exe" > /dev/null 2>&1 || die "$exe: not an ELF executable"
  needed=$(readelf -d "$exe" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
  ldd "$exe" | awk -v exe="$exe" -v needed="$needed" '
    BEGIN { n = split(needed, list, "\n"); for (i = 1; i <= n; i++) want[list[i]] = 1 }
    /not found/ { print "MISSING " $1 " " exe; next }
    ($1 in want) && $3 ~ /^\// { print $3 }'
done | sort -u)
missing=$(grep '^MISSING' <<< "$libs" || true)
[[ -z $missing ]] || die "not found by the loader: $(head -1 <<< "$missing" | cut -d' ' -f2-)"
for lib in $libs; do
  # dpkg knows a library by the path its package installed; /lib is a link to /usr/lib on Debian 12 (merged /usr).
  owner=$(dpkg -S "$lib" 2> /dev/null || dpkg -S "$(realpath "$lib")" 2> /dev/null ||
          dpkg -S "${lib#/usr}" 2> /dev/null || dpkg -S "/usr$lib" 2> /dev/null) || die "no Debian package holds $lib"
  echo "${owner%%:*}"
done | sed 's/, /\n/g' | sort -u
