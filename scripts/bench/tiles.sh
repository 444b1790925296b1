#!/usr/bin/env bash
# One frame in tiles: the 1M-triangle sphere of sphere-1m.py (through irsig-import and
# irsig-flatten), a SIZE x SIZE frame with SS x SS supersampling, traced whole and in 4 and
# 16 tiles of a grid, each tile a process of its own run one after the other (as a node runs
# the tasks of a job array), every process given all cores; then the tiles merged. Prints the
# wall time and peak memory (max RSS) of every process, and checks with cmp that the merged
# radiance EXR, truth EXR, map, counts and LUT are the whole frame's bytes. BENCHMARKS.md
# ("tiles") reports its output.
#
#   scripts/bench/tiles.sh [SIZE] [SS]    # defaults 4096 and 4
#
# Builds the release tools first; needs python3 and GNU time (/usr/bin/time). Scratch space:
# about 1.5 GB per copy of a 4096^2 frame's EXRs, under $TMPDIR.
set -euo pipefail
cd "$(dirname "$0")/../.."
size=${1:-4096}
ss=${2:-4}
repo=$PWD

nice -n 10 cargo build --quiet --release --bins
bin=$repo/target/release
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
materials=$repo/formats/canonical/samples/materials.ron

echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')), $(free -g | awk '/^Mem:/{print $2}') GiB;" \
  "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

cd "$work"
python3 "$repo/scripts/bench/sphere-1m.py"
"$bin/irsig-import" big.obj --materials "$materials" |
  "$bin/irsig-flatten" scene.ron --object big.ron=- -o scene.raw
rm -f big.obj big.glb big.fac
# The sphere (r = 10 m at (100, 0, 5)) from 30 m west of its centre: it fills most of the
# frame, the terrain the rest below the horizon.
cat > view.ron <<VIEW
LookAt(position_m: (70.0, 0.0, 5.0), target_m: (100.0, 0.0, 5.0), pixels: ($size, $size), fov_deg: (45.0, 45.0))
VIEW
echo "scene: 1 000 000 triangles, raw scene $(stat -c %s scene.raw) bytes; frame ${size}x${size}, ${ss}x${ss} rays per pixel"

trace=("$bin/irsig-trace" --scene scene.raw --materials "$materials" --view view.ron
  --atmosphere us-std-1976 --supersample "$ss")

# Runs a command under nice and GNU time; prints "label wall_s max_rss_mib".
measure() {
  local label=$1
  shift
  /usr/bin/time -f '%e %M' -o time.txt nice -n 10 "$@"
  read -r wall kib < time.txt
  printf '%-28s %9.2f s %8.0f MiB\n' "$label" "$wall" "$((kib / 1024))"
}

mkdir whole
measure "whole frame" "${trace[@]}" -o whole/frame

for grid in 2x2 4x4; do
  n=$(( ${grid%x*} * ${grid#*x} ))
  mkdir "tiles-$grid" "merged-$grid"
  total=0
  for i in $(seq "$n"); do
    line=$(measure "tile $i/$grid" "${trace[@]}" --tile "$i/$grid" -o "tiles-$grid/t$(printf %02d "$i")")
    echo "$line"
    total=$(echo "$total + $(echo "$line" | awk '{print $(NF-3)}')" | bc)
  done
  printf '%-28s %9.2f s\n' "all $n tiles of $grid" "$total"
  measure "merge $grid: radiance, counts" "$bin/irsig-merge" "tiles-$grid"/*.radiance.exr \
    --radiance-exr "merged-$grid/frame.radiance.exr" --dc-png "merged-$grid/frame.dc.png" \
    --lut "merged-$grid/frame.lut.txt"
  measure "merge $grid: truth, map" "$bin/irsig-merge" "tiles-$grid"/*.truth.exr \
    --truth-exr "merged-$grid/frame.truth.exr" --map-png "merged-$grid/frame.map.png"
  for f in radiance.exr truth.exr map.png dc.png lut.txt; do
    cmp "whole/frame.$f" "merged-$grid/frame.$f"
  done
  echo "merged $grid: every file byte-identical to the whole frame's"
  rm -rf "tiles-$grid" "merged-$grid"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
