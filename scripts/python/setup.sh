#!/usr/bin/env sh
# The Python package's test environment: a virtual environment of its own (target/py-venv,
# or under CARGO_TARGET_DIR), made on the first run with the system's python3 (3.9 or
# later), into which pip installs maturin, numpy, xarray, pytest and matplotlib (the
# README's example plots) from the package index (about 30 s once, seconds after). Prints
# the environment's path on standard output; pip's words go to standard error.
#
# scripts/test.sh runs it in the background while the Rust tests build, since it waits on
# the network more than on the CPU; scripts/python/test.sh runs it again (seconds when
# everything is installed).
#
# A missing python3, venv module or pip fails here, saying what to install: nothing is
# skipped.
set -eu
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-target}"
case "$target" in /*) ;; *) target="$PWD/$target" ;; esac
venv="$target/py-venv"
python="${PYTHON:-python3}"
if ! command -v "$python" >/dev/null 2>&1; then
  echo "python-tests: $python is not installed (Debian: apt-get install python3 python3-venv python3-pip)" >&2
  exit 1
fi
if [ ! -x "$venv/bin/python" ]; then
  mkdir -p "$target"
  if ! "$python" -m venv "$venv" >&2; then
    rm -rf "$venv"
    echo "python-tests: $python cannot make a virtual environment (Debian: apt-get install python3-venv)" >&2
    exit 1
  fi
fi
if ! "$venv/bin/python" -m pip --version >/dev/null 2>&1; then
  echo "python-tests: $venv has no pip (Debian: apt-get install python3-pip python3-venv)" >&2
  exit 1
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
  'maturin>=1.9.4,<2' 'numpy>=1.22' 'xarray>=2022.6' 'pytest>=7' 'matplotlib>=3.5' >&2
echo "$venv"
