#!/usr/bin/env sh
# irsig-therm's cost: a day at 5-minute steps (no spin-up, one shadow ray per facet and
# step, 16 hemisphere rays per facet) of the benchmark scene at N triangles (default 1M and
# 100k: scripts/bench/therm-scene.py), under the August TMY3 sample
# (formats/samples/golden-tmy3-aug.epw). Prints GNU time's wall and CPU figures and the
# CPU nanoseconds per facet-step. Run from the repository root after
# `cargo build --release -p irsig-therm`:
#
#     sh scripts/bench/therm.sh            # 1000000 and 100000
#     sh scripts/bench/therm.sh 250000
set -eu
root=$(pwd)
therm="$root/target/release/irsig-therm"
[ -x "$therm" ] || { echo "therm.sh: build first: cargo build --release -p irsig-therm" >&2; exit 1; }
[ "$#" -gt 0 ] || set -- 1000000 100000
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for n in "$@"; do
  mkdir -p "$work/$n"
  (cd "$work/$n" && python3 "$root/scripts/bench/therm-scene.py" "$n") >&2
  facets=$(python3 -c "import struct;b=open('$work/$n/scene.raw','rb').read(48);print(struct.unpack_from('<I',b,40)[0])")
  /usr/bin/time -f "%e %U %S %M" -o "$work/$n/time" "$therm" "$work/$n/scene.raw" \
    --materials "$work/$n/materials.ron" --weather "$root/formats/samples/golden-tmy3-aug.epw" \
    --at 2001-08-06T00:00-07:00 --at 2001-08-07T00:00-07:00 --spin-up-h 0 \
    --shadow-samples 1 --hemisphere-rays 16 -o "$work/$n/out"
  read -r wall user sys rss < "$work/$n/time"
  python3 - "$facets" "$wall" "$user" "$sys" "$rss" <<'PY'
import sys
facets, wall, user, sys_, rss = int(sys.argv[1]), *map(float, sys.argv[2:6])
steps = 288
print(f"{facets} facets: {wall:.1f} s wall, {user + sys_:.1f} s CPU, {rss / 1024:.0f} MiB peak; "
      f"{(user + sys_) / (facets * steps) * 1e9:.0f} ns CPU per facet-step")
PY
done
