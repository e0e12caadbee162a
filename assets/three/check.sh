#!/usr/bin/env bash
# Checks the pinned copy of three.js in this folder against the npm registry's tarball.
#
#   assets/three/check.sh [TARBALL]
#
# Without TARBALL it fetches the pinned version with `npm pack`. The tarball's sha512 must be the
# `integrity` PINNED records (the registry's own hash of that version), every file PINNED lists
# must be byte-identical to the tarball's file of the same path, and the folder may hold nothing
# else besides PINNED, this script and README.md. Prints one line per file and exits non-zero on
# the first difference.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
field() { sed -n "s/^$1 //p" "$here/PINNED"; }
package=$(field package)
version=$(field version)
integrity=$(field integrity)
files=$(sed -n '/^files$/,$p' "$here/PINNED" | tail -n +2)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ $# -ge 1 ]; then
  tarball=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
else
  (cd "$work" && npm pack --silent "$package@$version" >/dev/null)
  tarball="$work/$package-$version.tgz"
fi

actual="sha512-$(node -e 'process.stdout.write(require("crypto").createHash("sha512")
  .update(require("fs").readFileSync(process.argv[1])).digest("base64"))' "$tarball")"
if [ "$actual" != "$integrity" ]; then
  echo "error: $tarball: sha512 $actual is not the pinned $integrity" >&2
  exit 1
fi
echo "tarball $package@$version: $actual"

tar -xzf "$tarball" -C "$work"
for f in $files; do
  if ! cmp -s "$here/$f" "$work/package/$f"; then
    echo "error: assets/three/$f differs from $package@$version's package/$f" >&2
    exit 1
  fi
  echo "same: $f"
done

# Nothing else in the folder: a file added by hand would be inlined unchecked.
extra=$(cd "$here" && find . -type f ! -name PINNED ! -name check.sh ! -name README.md | sed 's|^\./||' | sort |
  comm -23 - <(printf '%s\n' $files | sort))
if [ -n "$extra" ]; then
  echo "error: assets/three holds files PINNED does not list: $extra" >&2
  exit 1
fi
echo "assets/three is $package@$version, verbatim"
