#!/usr/bin/env bash
# Stops the local Slurm cluster that scripts/slurm/start-local-cluster.sh started (and
# scripts/test.sh starts for tests/tests/slurm.rs): every slurmd, slurmctld and munged,
# each only when its pid file names a running process of that name. Needs root, like the start; the
# next `sh scripts/test.sh` starts them again.
#
#   sudo scripts/slurm/stop-local-cluster.sh
set -euo pipefail
if [ $# -gt 0 ]; then
  echo "stop-local-cluster: takes no arguments (usage: stop-local-cluster.sh)" >&2
  exit 2
fi
exec "$(dirname "$0")/start-local-cluster.sh" --stop
