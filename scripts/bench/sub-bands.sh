#!/usr/bin/env bash
# Frame time against the number of sub-bands (irsig-trace --sub-bands): the quickstart
# scene (pipelines/quickstart, 512 x 384 pixels) through the built-in US Standard 1976
# atmosphere, the band model and K = 4, 16, 64 and the full grid, each the median of RUNS
# runs of the whole process (reading the inputs, collapsing the spectral atmosphere over
# the sub-bands, precomputing their skies, rendering, writing the EXRs). Prints one line
# per setting: wall time and its ratio to the band model. BENCHMARKS.md ("Sub-bands")
# reports its output.
#
#   scripts/bench/sub-bands.sh [RUNS]    # default 5
#
# Builds the release tools first; needs GNU time (/usr/bin/time).
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${1:-5}
repo=$PWD
nice -n 10 cargo build --quiet --release -p irsig-trace -p irsig-flatten
bin=$repo/target/release
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
q=$repo/pipelines/quickstart

echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$bin/irsig-flatten" "$q/scene.ron" --materials "$q/materials.ron" -o "$work/scene.raw"

# The median wall time (s) of $runs runs of the command.
median() {
  local times=()
  for _ in $(seq "$runs"); do
    /usr/bin/time -f '%e' -o "$work/time.txt" nice -n 10 "$@" >/dev/null
    times+=("$(cat "$work/time.txt")")
  done
  printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'
}

band=""
for k in 1 4 16 64 full; do
  t=$(median "$bin/irsig-trace" --scene "$work/scene.raw" --materials "$q/materials.ron" \
    --view "$q/view.ron" --atmosphere us-std-1976 --sub-bands "$k" -o "$work/frame" --no-dc)
  band=${band:-$t}
  printf 'sub-bands %-5s %7.3f s  %5.2f x the band model\n' "$k" "$t" "$(echo "$t / $band" | bc -l)"
done
