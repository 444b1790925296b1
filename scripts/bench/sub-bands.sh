#!/usr/bin/env bash
# Frame time against the number of sub-bands (irsig-trace --sub-bands), through the built-in
# US Standard 1976 atmosphere: the band model and K = 4, 16, 64 and the full grid, each the
# median of RUNS runs of the whole process (reading the inputs, building the BVH,
# collapsing the spectral atmosphere over the sub-bands, precomputing their skies,
# rendering, writing the EXRs). Prints one line per setting: wall time and its ratio to the
# band model. BENCHMARKS.md ("Sub-bands") reports its output. SCENE is
#
#   quickstart  the quickstart (pipelines/quickstart, 512 x 384 pixels), the default;
#   sphere-1m   the 1M-triangle sphere of sphere-1m.py (through irsig-import and
#               irsig-flatten) over the terrain, 512 x 384 pixels, the sphere filling most
#               of the frame, the terrain below it and the sky above.
#
#   scripts/bench/sub-bands.sh [RUNS] [SCENE]    # defaults 5, quickstart
#
# Builds the release tools first; needs GNU time (/usr/bin/time), and python3 for sphere-1m.
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${1:-5}
scene=${2:-quickstart}
repo=$PWD
nice -n 10 cargo build --quiet --release -p irsig-trace -p irsig-flatten -p irsig-import
bin=$repo/target/release
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
case $scene in
  quickstart)
    q=$repo/pipelines/quickstart
    materials=$q/materials.ron
    view=$q/view.ron
    "$bin/irsig-flatten" "$q/scene.ron" --materials "$materials" -o "$work/scene.raw"
    ;;
  sphere-1m)
    materials=$repo/formats/canonical/samples/materials.ron
    view=$work/view.ron
    (
      cd "$work"
      python3 "$repo/scripts/bench/sphere-1m.py"
      "$bin/irsig-import" big.obj --materials "$materials" |
        "$bin/irsig-flatten" scene.ron --object big.ron=- -o scene.raw
      rm -f big.obj big.glb big.fac
    )
    # The sphere (r = 10 m at (100, 0, 5)) from 30 m west of its centre, as in tiles.sh.
    echo 'LookAt(position_m: (70.0, 0.0, 5.0), target_m: (100.0, 0.0, 5.0), pixels: (512, 384), fov_deg: (60.0, 45.0))' >"$view"
    echo "scene: 1 000 000 triangles, raw scene $(stat -c %s "$work/scene.raw") bytes"
    ;;
  *)
    echo "unknown scene '$scene': quickstart or sphere-1m" >&2
    exit 2
    ;;
esac

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
  t=$(median "$bin/irsig-trace" --scene "$work/scene.raw" --materials "$materials" \
    --view "$view" --atmosphere us-std-1976 --sub-bands "$k" -o "$work/frame" --no-dc)
  band=${band:-$t}
  printf 'sub-bands %-5s %7.3f s  %5.2f x the band model\n' "$k" "$t" "$(echo "$t / $band" | bc -l)"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
