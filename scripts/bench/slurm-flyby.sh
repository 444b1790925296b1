#!/usr/bin/env bash
# Frames per minute of the thesis fly-by (pipelines/thesis-flyby.ron: flatten, 24 traced
# frames at 256 x 256, a contact sheet): irsig-run on this machine's cores against the same
# pipeline as a Slurm job array (irsig-run --emit-slurm) on the local cluster of
# scripts/slurm/start-local-cluster.sh; and the scheduler's overhead per task, from an array
# of empty tasks. BENCHMARKS.md ("Slurm") reports its output.
#
#   scripts/slurm/start-local-cluster.sh      # as root, once
#   scripts/bench/slurm-flyby.sh [RUNS]       # RUNS of each (default 3); prints a table
#
# Builds the release tools first. Each run starts from nothing (--force), so every step of
# the fly-by runs every time.
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${1:-3}

for program in sbatch squeue sinfo; do
  command -v "$program" >/dev/null 2>&1 ||
    { echo "slurm-flyby: $program is not on PATH (scripts/slurm/start-local-cluster.sh)" >&2; exit 1; }
done
sinfo --noheader --format=%T | grep -qE '^(idle|mixed)$' ||
  { echo "slurm-flyby: no idle node: start the cluster with scripts/slurm/start-local-cluster.sh" >&2; exit 1; }

nice -n 10 cargo build --quiet --release --bins
run=$PWD/target/release/irsig-run
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r pipelines/thesis-flyby pipelines/thesis-flyby.ron "$work/"
rm -rf "$work/thesis-flyby/build"

now() { date +%s.%N; }
elapsed() { printf '%.2f' "$(echo "$2 - $1" | bc)"; }

# Waits until none of the jobs ($1: comma-separated ids) is queued; fails on a task that did
# not complete.
wait_jobs() {
  while [ -n "$(squeue --noheader --jobs "$1" 2>/dev/null)" ]; do sleep 0.1; done
  for id in ${1//,/ }; do
    if scontrol --oneliner show job "$id" | grep -v 'JobState=COMPLETED' | grep -q .; then
      echo "slurm-flyby: job $id did not complete:" >&2
      scontrol --oneliner show job "$id" | grep -v 'JobState=COMPLETED' >&2
      exit 1
    fi
  done
}

median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')), $(free -g | awk '/^Mem:/{print $2}') GiB;" \
  "$(sbatch --version); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

local_s=()
slurm_s=()
for i in $(seq "$runs"); do
  t0=$(now)
  (cd "$work" && "$run" --quiet --force --threads "$(nproc)" thesis-flyby.ron)
  t1=$(now)
  local_s+=("$(elapsed "$t0" "$t1")")
  cp -r "$work/thesis-flyby/build" "$work/local-build"

  t0=$(now)
  (cd "$work" && "$run" --quiet --force --emit-slurm slurm thesis-flyby.ron)
  ids=$(cd "$work" && sh slurm/submit.sh | cut -d' ' -f1 | paste -sd, -)
  wait_jobs "$ids"
  t1=$(now)
  slurm_s+=("$(elapsed "$t0" "$t1")")
  diff -r "$work/local-build" "$work/thesis-flyby/build" >/dev/null ||
    { echo "slurm-flyby: the job array's outputs differ from irsig-run's" >&2; exit 1; }
  rm -rf "$work/local-build"
  echo "run $i: irsig-run ${local_s[-1]} s, Slurm ${slurm_s[-1]} s" >&2
done

# Empty tasks: all that is left of a task is the scheduler's part (allocation, launch,
# completion, and the wait for the controller's next scheduling pass).
empty_s=()
cpus=$(nproc)
for i in $(seq "$runs"); do
  t0=$(now)
  id=$(sbatch --parsable --array=1-48 --cpus-per-task=1 --mem=16M --output=/dev/null --wrap true)
  wait_jobs "${id%%;*}"
  t1=$(now)
  empty_s+=("$(elapsed "$t0" "$t1")")
done

local_m=$(printf '%s\n' "${local_s[@]}" | median)
slurm_m=$(printf '%s\n' "${slurm_s[@]}" | median)
empty_m=$(printf '%s\n' "${empty_s[@]}" | median)
tasks=26 # flatten, 24 frames, contact sheet
echo
echo "| what | wall, each run (s) | median (s) | fly-by frames per minute |"
echo "| --- | --- | --- | --- |"
echo "| irsig-run --threads $cpus | ${local_s[*]} | $local_m | $(echo "scale=1; 24 * 60 / $local_m" | bc) |"
echo "| Slurm job array (emit, submit, wait) | ${slurm_s[*]} | $slurm_m | $(echo "scale=1; 24 * 60 / $slurm_m" | bc) |"
echo "| 48 empty tasks, $cpus at a time | ${empty_s[*]} | $empty_m | |"
echo
printf 'scheduler overhead per task, empty tasks: %.2f s of a CPU slot\n' \
  "$(echo "scale=4; $empty_m * $cpus / 48" | bc)"
printf 'scheduler overhead per task, fly-by (%d tasks, %d slots): %.2f s of a CPU slot\n' \
  "$tasks" "$cpus" "$(echo "scale=4; ($slurm_m - $local_m) * $cpus / $tasks" | bc)"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
