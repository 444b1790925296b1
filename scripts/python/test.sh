#!/usr/bin/env sh
# The Python package's tests (python/tests, pytest), run by scripts/test.sh after the Rust
# tests, in the environment scripts/python/setup.sh makes (a virtual environment under the
# target folder with maturin, numpy, xarray, pytest and matplotlib from the package index).
# `maturin develop` then builds the extension module in the release profile into the same
# target folder as the Rust build, and the tests compare it with irsig-flatten and
# irsig-trace of that build.
#
# A missing python3, venv module or pip fails, saying what to install: nothing is skipped.
#
#     sh scripts/python/test.sh            # every Python test
#     sh scripts/python/test.sh -k threads # arguments go to pytest
set -eu
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-target}"
case "$target" in /*) ;; *) target="$PWD/$target" ;; esac
venv=$(sh scripts/python/setup.sh)
# The tools as the Rust tests build them (irsig_tests::bin_path), and the module with the
# features of the workspace's test build (python/Cargo.toml): after `cargo test
# --workspace` neither compiles irsig's crates again.
echo "python-tests: building the tools (release profile), then the extension module" >&2
cargo build --quiet --release --workspace --bins --features irsig-tests/test-tools
VIRTUAL_ENV="$venv" "$venv/bin/maturin" develop --quiet --release -m python/Cargo.toml
IRSIG_BIN="$target/release" exec "$venv/bin/python" -m pytest python/tests "$@"
