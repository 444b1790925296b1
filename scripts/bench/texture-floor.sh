#!/usr/bin/env bash
# The texture's cost floor (a textured 1024² frame within 1.25× of an untextured one),
# measured so that the VM's drift falls on every case alike: the tracer bench's
# `frame_1024` cases (plain, field, field-footprint, maps, footprint) one at a time, three
# samples an invocation, every case of every build in turn, ROUNDS rounds a scene. Prints,
# per scene and build, each textured case's fastest sample over the plain frame's fastest
# of the same build, and in brackets the median over the rounds of the ratio within a round.
# BENCHMARKS.md ("texture: the point field within the floor") reports its output.
#
#   scripts/bench/texture-floor.sh [ROUNDS] [BENCH_BINARY ...]
#
# ROUNDS defaults to 10 at 1k triangles (half that at 100k and 1M). With no binary, the
# working tree's bench is built (release profile, as the tools ship) and measured alone;
# an A/B passes two binaries built from two trees, each in its own target directory
# (`cargo bench --profile release -p irsig-tracer --bench trace --no-run` prints the path).
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-10}
shift || true
if [ "$#" -eq 0 ]; then
  bin=$(nice -n 10 cargo bench --quiet --profile release -p irsig-tracer --bench trace --no-run \
    --message-format=json | sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1)
  set -- "$bin"
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
cases="plain field field-footprint maps footprint"
for scene in 0 1 2; do
  n=$rounds
  [ "$scene" -eq 0 ] || n=$(((rounds + 1) / 2))
  for round in $(seq "$n"); do
    for case in $cases; do
      build=0
      for bin in "$@"; do
        build=$((build + 1))
        # divan's line for the case: its name, then the fastest sample and its unit.
        "$bin" --bench "frame_1024::$scene::$case\$" --sample-count 3 |
          awk -v s="$scene" -v r="$round" -v b="$build" -v c="$case" \
            '$2 == c { v = $3; if ($4 == "s") v *= 1000; print s, r, b, c, v }'
      done
    done
  done
done > "$work/all.txt"
python3 - "$work/all.txt" "$@" <<'EOF'
import collections, statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
builds = sys.argv[2:]
fastest = collections.defaultdict(lambda: float("inf"))
rounds = collections.defaultdict(dict)
for scene, rnd, build, case, ms in rows:
    fastest[scene, build, case] = min(fastest[scene, build, case], float(ms))
    rounds[scene, build, rnd][case] = float(ms)
cases = ["field", "field-footprint", "maps", "footprint"]
print("| triangles | build | plain, ms | " + " | ".join(cases) + " |")
print("| ---: | --- | ---: | " + " | ".join("---" for _ in cases) + " |")
for scene, tris in [("0", "1 026"), ("1", "99 906"), ("2", "1 001 112")]:
    for b, name in enumerate(builds, 1):
        b = str(b)
        plain = fastest[scene, b, "plain"]
        if plain == float("inf"):
            continue
        cells = []
        for c in cases:
            within = [r[c] / r["plain"] for (s, bb, _), r in rounds.items()
                      if s == scene and bb == b and c in r and "plain" in r]
            cells.append(f"{fastest[scene, b, c] / plain:.2f} ({statistics.median(within):.2f})")
        print(f"| {tris} | {name} | {plain:.0f} | " + " | ".join(cells) + " |")
EOF
