#!/usr/bin/env bash
# The tolerance pilot's cost model against the clock: for the quickstart scene and the
# thesis experiment's scene, at each TOLERANCE, the relative cost the decision predicts
# (its chosen settings' cost over the reference settings': 8 bounces, 256 sky-view rays,
# the full grid, exact path terms, refinement to its target) against the measured one, the
# CPU seconds (user + system) of a rendering with the chosen settings over one with the
# reference settings, both applied from a decision file (no pilot in either). Also the
# pilot's own seconds against the chosen rendering's. Views are the cases' own, scaled to
# WIDTH pixels across (the reference rendering at full size takes an hour).
#
#   scripts/bench/tolerance-cost.sh [WIDTH] [TOLERANCE...]    # defaults 128, 1 0.3
#
# Prints one line per case and tolerance. Builds the release tools first; needs GNU time
# (/usr/bin/time) and python3. BENCHMARKS.md ("The tolerance pilot's cost model") reports
# its output.
set -euo pipefail
cd "$(dirname "$0")/../.."
width=${1:-128}
[ $# -gt 0 ] && shift
tolerances=(1 0.3)
[ $# -gt 0 ] && tolerances=("$@")
repo=$PWD
nice -n 10 cargo build --quiet --release -p irsig-trace -p irsig-flatten
bin=$repo/target/release
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

# A view file with its pixels scaled to WIDTH across, the aspect kept.
scaled_view() {
  python3 - "$1" "$2" "$width" <<'EOF'
import re, sys
src, dst, width = sys.argv[1], sys.argv[2], int(sys.argv[3])
text = open(src).read()
m = re.search(r"pixels:\s*\((\d+),\s*(\d+)\)", text)
w, h = int(m.group(1)), int(m.group(2))
height = max(1, round(h * width / w))
open(dst, "w").write(text[: m.start()] + f"pixels: ({width}, {height})" + text[m.end():])
EOF
}

# The decision with every choice set to its reference setting.
reference_decision() {
  python3 - "$1" "$2" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
def swap(m):
    block = m.group(0)
    ref = re.search(r'reference: "([^"]*)"', block).group(1)
    return re.sub(r'setting: "[^"]*"', f'setting: "{ref}"', block, count=1)
text = re.sub(r"\(\s*model:[^()]*?(?:\([^()]*\)[^()]*?)*\)", swap, text, flags=re.S)
open(sys.argv[2], "w").write(text)
EOF
}

# CPU seconds (user + system) of a command.
cpu() {
  /usr/bin/time -f "%U %S" -o "$work/time" "$@" >/dev/null 2>"$work/stderr" || {
    cat "$work/stderr" >&2
    return 1
  }
  awk '{ printf "%.2f", $1 + $2 }' "$work/time"
}

q=$repo/pipelines/quickstart
"$bin/irsig-flatten" "$q/scene.ron" --materials "$q/materials.ron" -o "$work/quickstart.raw"
scaled_view "$q/view.ron" "$work/quickstart.view.ron"
t=$repo/pipelines/thesis-experiment
"$bin/irsig-flatten" "$t/scene.ron" --materials "$t/materials.ron" -o "$work/thesis.raw"
scaled_view "$t/view.ron" "$work/thesis.view.ron"

printf '%-12s %6s %10s %10s %9s %10s %10s\n' case T predicted measured meas/pred pilot_s chosen_s
for case in quickstart:"$q/materials.ron" thesis:"$t/materials.ron"; do
  name=${case%%:*}
  materials=${case#*:}
  for tol in "${tolerances[@]}"; do
    trace=("$bin/irsig-trace" --scene "$work/$name.raw" --materials "$materials"
      --view "$work/$name.view.ron" --atmosphere us-std-1976)
    "${trace[@]}" --tolerance "$tol" --radiance-exr "$work/p.exr" \
      --decision-out "$work/chosen.ron" 2>"$work/pilot.txt"
    pilot=$(sed -n 's/.*pilot: [0-9]* pixels in \([0-9.]*\) s.*/\1/p' "$work/pilot.txt")
    predicted=$(sed -n 's/^  relative_cost: \([0-9.e-]*\),$/\1/p' "$work/chosen.ron")
    reference_decision "$work/chosen.ron" "$work/reference.ron"
    chosen=$(cpu "${trace[@]}" --decision "$work/chosen.ron" --radiance-exr "$work/c.exr")
    reference=$(cpu "${trace[@]}" --decision "$work/reference.ron" --radiance-exr "$work/r.exr")
    python3 - "$name" "$tol" "$predicted" "$chosen" "$reference" "$pilot" <<'EOF'
import sys
name, tol, predicted, chosen, reference, pilot = sys.argv[1:]
measured = float(chosen) / float(reference)
print(f"{name:<12} {tol:>6} {float(predicted):10.3f} {measured:10.3f} "
      f"{measured / float(predicted):9.2f} {float(pilot):10.2f} {float(chosen):10.2f}")
EOF
  done
done
