#!/usr/bin/env bash
# Single-ray traversal against Intel Embree on the same triangles and the same rays: the
# 1M-triangle scene of the tracer's shade profile (a UV sphere over a ground quad) seen by
# a 1024 x 1024 camera. crates/tracer/examples/traversal.rs writes the triangles and rays
# and times, on one thread, obvhs's bare traversal, the tracer's geometry (f64 clip,
# watertight test, f64 refinement) and bare obvhs with the rays in packets of 64
# consecutive ones (a route measured, not the tracer's: testing::BareObvhs::packet_pass);
# scripts/bench/embree_rays.cpp times rtcIntersect1 on the same files, one thread. RUNS
# rounds, the programs interleaved, each round a fresh process; prints the median ns per ray
# of each, per ray order (scanline, 8 x 8 tiles), and the ratios.
# With V3=1 a second irsig build with -C target-cpu=x86-64-v3 runs in the rounds too.
# BENCHMARKS.md ("traversal against Embree") reports its output.
#
#   scripts/bench/traversal-embree.sh [RUNS]     # default 5
#
# Needs Debian's libembree-dev (Embree 3) and g++.
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${1:-5}
repo=$PWD
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
nice -n 10 cargo build --quiet --release -p irsig-tracer --example traversal
tools=("irsig:$repo/target/release/examples/traversal")
if [ "${V3:-0}" = 1 ]; then
  RUSTFLAGS="-C target-cpu=x86-64-v3" nice -n 10 cargo build --quiet --release -p irsig-tracer \
    --example traversal --target-dir "$repo/target/x86-64-v3"
  tools+=("irsig-v3:$repo/target/x86-64-v3/release/examples/traversal")
fi
g++ -O2 -o "$work/embree_rays" scripts/bench/embree_rays.cpp -lembree3

echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for _ in $(seq "$runs"); do
  for t in "${tools[@]}"; do
    name=${t%%:*}
    "${t#*:}" "$work/rays" 2 1024 1 | awk -v n="$name" -F'|' '/^\| (scanline|tiles) /{gsub(/ /,"",$2); print n, $2, "bare", $3; print n, $2, "geometry", $4; print n, $2, "packets", $5}'
  done
  "$work/embree_rays" "$work/rays" 1 | awk -F'|' '/^\| (scanline|tiles) /{gsub(/ /,"",$2); print "embree", $2, "rtcIntersect1", $3}'
done > "$work/all.txt"
awk '{k=$1" "$2" "$3; v[k]=v[k]" "$4} END {for (k in v) print k, v[k]}' "$work/all.txt" | sort | while read -r tool order what values; do
  median=$(printf '%s\n' $values | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  echo "$order $tool $what $median"
done | sort > "$work/medians.txt"
printf '| order | traversal | median ns per ray | Embree / it |\n| --- | --- | ---: | ---: |\n'
while read -r order tool what ns; do
  embree=$(awk -v o="$order" '$1==o && $2=="embree" {print $4}' "$work/medians.txt")
  printf '| %s | %s %s | %s | %.2f |\n' "$order" "$tool" "$what" "$ns" "$(echo "$embree / $ns" | bc -l)"
done < "$work/medians.txt"
