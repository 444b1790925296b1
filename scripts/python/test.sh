#!/usr/bin/env sh
# The Python package's tests (python/tests, pytest), run by scripts/test.sh after the Rust
# tests: in a virtual environment of their own (target/py-venv, or under CARGO_TARGET_DIR),
# made on the first run with the system's python3 (3.9 or later), into which pip installs
# maturin, numpy, xarray, pytest and matplotlib (the README's example plots) from the package
# index (about 30 s once, seconds after).
# `maturin develop` then builds the extension module in the dev profile into the same
# target folder as the Rust build, and the tests compare it with irsig-flatten and
# irsig-trace of that build.
#
# A missing python3, venv module or pip fails here, saying what to install: nothing is
# skipped.
#
#     sh scripts/python/test.sh            # every Python test
#     sh scripts/python/test.sh -k threads # arguments go to pytest
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
  if ! "$python" -m venv "$venv"; then
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
  'maturin>=1.9.4,<2' 'numpy>=1.22' 'xarray>=2022.6' 'pytest>=7' 'matplotlib>=3.5'
# The tools as the Rust tests build them (irsig_tests::bin_path), and the module with the
# features of the workspace's test build (python/Cargo.toml): after `cargo test
# --workspace` neither compiles irsig's crates again.
echo "python-tests: building the tools (dev profile), then the extension module" >&2
cargo build --quiet --workspace --bins --features irsig-tests/test-tools
VIRTUAL_ENV="$venv" "$venv/bin/maturin" develop --quiet -m python/Cargo.toml
IRSIG_BIN="$target/debug" exec "$venv/bin/python" -m pytest python/tests "$@"
