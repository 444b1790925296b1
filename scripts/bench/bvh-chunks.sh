#!/usr/bin/env bash
# What building the BVH in chunks trades (crates/tracer/examples/bvh_chunks.rs): for the
# 1M-triangle sphere over a ground quad and the ThRend side-by-side's terrain and box, one
# BVH over every triangle against chunks of at most 16k (the tracer's), 32k and 64k
# triangles; per pair the build on rayon's threads and on one, the primary rays on one
# thread (fastest of ROUNDS in a process) and the build's peak resident memory (GNU time,
# a process per pair, which holds the scene's f64 mesh, about 24 MB, as well). Interleaved:
# RUNS rounds of every pair, medians printed. BENCHMARKS.md ("tracer: the BVH in chunks")
# reports its output.
#
#   scripts/bench/bvh-chunks.sh [RUNS] [ROUNDS]    # defaults 3 and 3
#
# Needs GNU time (/usr/bin/time).
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${1:-3}
rounds=${2:-3}
nice -n 10 cargo build --quiet --release -p irsig-tracer --example bvh_chunks
bin=$PWD/target/release/examples/bvh_chunks
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for _ in $(seq "$runs"); do
  for scene in sphere terrain; do
    for chunk in whole 16384 32768 65536; do
      for threads in 2 1; do
        /usr/bin/time -f '%M' -o "$work/rss" env RAYON_NUM_THREADS=$threads "$bin" "$scene" "$chunk" "$rounds" |
          sed -E 's/.*triangles, ([0-9]+) chunks, build ([0-9.]+) s on ([0-9]+) threads, rays ([0-9]+) ns.*/\1 \2 \3 \4/' |
          while read -r n b t r; do echo "$scene $chunk $threads $n $b $r $(cat "$work/rss")"; done
      done
    done
  done
done > "$work/all.txt"
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
printf '| scene | chunk | chunks | build, 2 threads (s) | build, 1 thread (s) | rays (ns) | peak RSS, 2 threads (MiB) |\n| --- | --- | ---: | ---: | ---: | ---: | ---: |\n'
for scene in sphere terrain; do
  for chunk in whole 16384 32768 65536; do
    two=$(awk -v s="$scene" -v c="$chunk" '$1 == s && $2 == c && $3 == 2' "$work/all.txt")
    one=$(awk -v s="$scene" -v c="$chunk" '$1 == s && $2 == c && $3 == 1' "$work/all.txt")
    printf '| %s | %s | %s | %.3f | %.3f | %.0f | %.0f |\n' "$scene" "$chunk" \
      "$(echo "$two" | awk '{print $4}' | median)" \
      "$(echo "$two" | awk '{print $5}' | median)" \
      "$(echo "$one" | awk '{print $5}' | median)" \
      "$(printf '%s\n%s\n' "$two" "$one" | awk '{print $6}' | median)" \
      "$(echo "$two" | awk '{print $7 / 1024}' | median)"
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
