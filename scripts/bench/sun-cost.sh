#!/usr/bin/env bash
# What the sun costs a frame (issue 30's floor: at most 1.5x the night time at 1024^2 on the
# 1M-triangle scene, one shadow ray per hit): the 1M-triangle sphere of sphere-1m.py over
# the terrain, seen from 30 m, traced through one LOWTRAN7 solar build (8-14 um, the plan's
# grid) without and with the sun, and with 4 disk samples. Interleaved: RUNS rounds of
# night, sun, sun with 4 shadow rays, each a process of its own given all cores. Prints
# every run's wall and CPU seconds (user + system, GNU time) and the medians' ratios to
# night, then the same with the fixed cost taken off: reading the scene, building the BVH and
# the atmosphere's tables, measured as the night run of an 8 x 8 view of the same scene.
# BENCHMARKS.md ("the sun's cost") reports its output.
#
#   scripts/bench/sun-cost.sh [SIZE] [RUNS]    # defaults 1024 and 3
#
# Builds the release tools first; needs python3, GNU time (/usr/bin/time) and LOWTRAN7
# (IRSIG_LOWTRAN, or lowtran7 on PATH: scripts/atmosphere/install-lowtran.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
size=${1:-1024}
runs=${2:-3}
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
# The sphere (r = 10 m at (100, 0, 5)) from 30 m west of its centre, as scripts/bench/tiles.sh
# sees it: it fills most of the frame, the terrain the rest below the horizon. The sun is in
# the south-west, 40 deg from the zenith, so the sphere has a lit side, a terminator and a
# shadow on the terrain in view.
cat > view.ron <<VIEW
LookAt(position_m: (70.0, 0.0, 5.0), target_m: (100.0, 0.0, 5.0), pixels: ($size, $size), fov_deg: (45.0, 45.0))
VIEW
sed "s/pixels: ([0-9]*, [0-9]*)/pixels: (8, 8)/" view.ron > fixed.ron
"$bin/irsig-atmos" plan --scene scene.raw --view view.ron --atmosphere us-std-1976 \
  --sun-zenith-deg 40 --day-of-year 172 -o plan >/dev/null
"$bin/irsig-atmos" build plan -o noon.spa
echo "scene: 1 000 000 triangles; frame ${size}x${size}, 1 ray per pixel; atmosphere: $(stat -c %s noon.spa) bytes"

trace=("$bin/irsig-trace" --scene scene.raw --materials "$materials"
  --atmosphere noon.spa --band 8-14)
night=(--view view.ron)
sun=(--view view.ron --sun-zenith-deg 40 --sun-azimuth-deg 225)
disk=("${sun[@]}" --sun-shadow-rays 4)

# Runs a case under nice and GNU time; appends "case wall_s cpu_s" to all.txt.
measure() {
  local case=$1
  shift
  /usr/bin/time -f '%e %U %S' -o time.txt nice -n 10 "${trace[@]}" "$@" -o "out-$case"
  rm -f "out-$case".*
  read -r wall user sys < time.txt
  echo "$case $wall $(echo "$user + $sys" | bc)" | tee -a all.txt
}
for _ in $(seq "$runs"); do
  measure fixed --view fixed.ron
  measure night "${night[@]}"
  measure sun "${sun[@]}"
  measure sun-4 "${disk[@]}"
done
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
col() { awk -v c="$1" -v k="$2" '$1 == c {print $k}' all.txt | median; }
ratio() { echo "($(col "$1" "$2") - $3) / ($(col night "$2") - $3)" | bc -l; }
printf '| case | wall (s) | CPU (s) | wall / night | CPU / night | frame CPU / night frame CPU |\n'
printf '| --- | ---: | ---: | ---: | ---: | ---: |\n'
for c in night sun sun-4; do
  printf '| %s | %.2f | %.2f | %.2f | %.2f | %.2f |\n' "$c" "$(col "$c" 2)" "$(col "$c" 3)" \
    "$(ratio "$c" 2 0)" "$(ratio "$c" 3 0)" "$(ratio "$c" 3 "$(col fixed 3)")"
done
printf 'fixed cost (8 x 8 view): %.2f s wall, %.2f s CPU\n' "$(col fixed 2)" "$(col fixed 3)"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
