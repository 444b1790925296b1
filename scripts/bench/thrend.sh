#!/usr/bin/env bash
# irsig against ThRend (the open thermal renderer on Intel Embree, github.com/jpaguerre/ThRend)
# on one scene: the bumpy terrain of 999,698 triangles and the 12-triangle mirror box of
# thrend-scene.py, the same pinhole camera, one primary ray per pixel and one reflection ray
# per hit in both, no atmosphere, no supersampling. BENCHMARKS.md ("irsig against ThRend")
# reports its output.
#
#   scripts/bench/thrend.sh THREND_CHECKOUT [PAIRS] [SIZES]   # defaults 5 and "1024 512"
#
# THREND_CHECKOUT is a clone of ThRend's repository (its ThRend/ sources are read, never
# changed: they are copied to scratch space). ThRend is a Visual Studio project for Embree
# 3.5; the script builds it with g++ against Debian's Embree 3.13 after three one-line fixes
# it makes itself, each found by the Embree call it concerns:
#   1. the vertex buffers (rtcSetGeometryBuffer of RTC_BUFFER_TYPE_VERTEX) are declared with
#      the index count as their item count; Embree 3.13 checks it against the buffer's size,
#      so it becomes the vertex count of the shared buffer (rtcNewSharedBuffer);
#   2. the quad geometry's id (what rtcAttachGeometry returns for the RTC_GEOMETRY_TYPE_QUAD
#      geometry) is left at 0, the triangles' id, when a scene has no quads, so every
#      triangle hit is taken for a quad; it starts at RTC_INVALID_GEOMETRY_ID;
#   3. RTCRay.mask is never set, and Embree 3.13 (built with ray masks) skips geometry the
#      mask leaves out; every RTCRay gets mask 0xFFFFFFFF.
# It also sets the OpenMP thread count (the constant passed to omp_set_num_threads, 8 in the
# source) to 1 and 2, one binary each, and supplies empty stand-ins for the Windows headers
# ThRend includes but does not use (windows.h, process.h, GL/glew.h for GLuint).
#
# Each round runs, one after the other: ThRend on 1 thread, then irsig's rows on 1 thread;
# ThRend on 2 threads, then irsig's rows on 2 threads and the end-to-end run. The 1-thread
# runs of both are pinned to one CPU (taskset), so neither's BVH build uses the second.
# Prints per row the median wall time and peak resident memory (GNU time, %e and %M) of
# PAIRS rounds and the ratio irsig / ThRend of the medians. Rows:
#   - irsig's radiance EXR + DC PNG + LUT (from the binary raw scene), 1 and 2 threads;
#   - irsig's -o (radiance and truth EXRs, map, DC PNG, LUT), 1 and 2 threads;
#   - end-to-end from text: irsig-import of both OBJ files | irsig-flatten | irsig-trace -o,
#     against ThRend, which reads its own text input (AVS UCD) in every run.
# ThRend writes four PNGs and a text file of apparent temperatures in every run.
# First it checks that both see the same geometry: per pixel, terrain, box or nothing (sky
# or, for irsig, the background terrain beyond the mesh), from irsig's interaction map and
# ThRend's real.png (surface temperature in grey), and prints the share of pixels that agree.
#
# Needs (Debian packages): g++ (its libgomp for -fopenmp), libembree-dev, libfreeimage-dev,
# python3, netpbm (pngtopnm), time (GNU time), util-linux (taskset), bc,
# and a Rust toolchain for the release build. It installs nothing. Scratch space: about
# 300 MB under $TMPDIR.
set -euo pipefail
if [ $# -lt 1 ] || [ ! -f "$1/ThRend/main.cpp" ]; then
  echo "usage: $0 THREND_CHECKOUT [PAIRS] [SIZES]  (THREND_CHECKOUT/ThRend/main.cpp must exist)" >&2
  exit 2
fi
src=$(cd "$1/ThRend" && pwd)
pairs=${2:-5}
sizes=${3:-1024 512}
cd "$(dirname "$0")/../.."
repo=$PWD

nice -n 10 cargo build --quiet --release --bins
bin=$repo/target/release
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "machine: $(nproc) CPUs ($(lscpu | sed -n 's/^Model name: *//p')), $(free -g | awk '/^Mem:/{print $2}') GiB;" \
  "Embree $(dpkg-query -W -f '${Version}' libembree-dev 2>/dev/null || echo '?');" \
  "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

# --- ThRend: copy, fix, build one binary per thread count ---
mkdir -p "$work/build/shim/GL"
: > "$work/build/shim/windows.h"
: > "$work/build/shim/process.h"
echo 'typedef unsigned int GLuint;' > "$work/build/shim/GL/glew.h"
for threads in 1 2; do
  b=$work/build/src$threads
  cp -r "$src" "$b"
  perl -0pi -e '
    /rtcNewSharedBuffer\(\s*\w+\s*,\s*(\w+)\.data\(\)/ or die "thrend.sh: no rtcNewSharedBuffer of a vector\n";
    my $v = $1;
    s/(rtcSetGeometryBuffer\(\s*\w+\s*,\s*RTC_BUFFER_TYPE_VERTEX\s*,[^;]*?,)\s*\w+\.size\(\)\s*\)/$1 $v.size())/g
      or die "thrend.sh: no vertex buffer to fix\n";
    /(\w+)\s*=\s*rtcNewGeometry\(\s*\w+\s*,\s*RTC_GEOMETRY_TYPE_QUAD\s*\)/ or die "thrend.sh: no quad geometry\n";
    my $g = $1;
    /(\w+)\s*=\s*rtcAttachGeometry\(\s*\w+\s*,\s*$g\s*\)/ or die "thrend.sh: no attach of $g\n";
    my $id = $1;
    s/^(\s*unsigned\s+int\s+$id)\s*;/$1 = RTC_INVALID_GEOMETRY_ID;/m or die "thrend.sh: no declaration of $id\n";
  ' "$b/EmbreeUtils.h"
  for f in "$b"/*.h "$b"/*.cpp; do
    perl -pi -e 's/^(\s*)RTCRay\s+(\w+)\s*;/$1RTCRay $2; $2.mask = 0xFFFFFFFFu;/' "$f"
  done
  grep -q 'mask = 0xFFFFFFFFu' "$b/main.cpp" || { echo "thrend.sh: no RTCRay in main.cpp" >&2; exit 1; }
  perl -0pi -e '
    /omp_set_num_threads\(\s*(\w+)\s*\)/ or die "thrend.sh: no omp_set_num_threads\n";
    my $n = $1;
    s/^(\s*const\s+int\s+$n\s*=\s*)\d+\s*;/${1}'"$threads"';/m or die "thrend.sh: no constant $n\n";
  ' "$b/main.cpp"
  (cd "$b" && nice -n 10 g++ -O3 -fopenmp -w -I"$work/build/shim" -I. -Iglm -include cassert \
    main.cpp -o "$work/build/thrend$threads" -lembree3 -lfreeimage)
done
echo "ThRend built: g++ $(g++ -dumpversion) -O3, $(cd "$1" && git rev-parse --short HEAD 2>/dev/null || echo 'not a git checkout')"

# Runs a command under nice and GNU time, appending "wall_s max_rss_kib" to file $1.
measure() {
  local out=$1
  shift
  /usr/bin/time -f '%e %M' -o "$work/time.txt" nice -n 10 "$@" > /dev/null
  cat "$work/time.txt" >> "$out"
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

for size in $sizes; do
  d=$work/$size
  mkdir -p "$d/thrend/bin" "$d/thrend/results" "$d/out" "$d/times"
  cd "$d"
  python3 "$repo/scripts/bench/thrend-scene.py" "$size"
  "$bin/irsig-import" box.obj --materials materials.ron > box.ron
  "$bin/irsig-import" terrain.obj --materials materials.ron |
    "$bin/irsig-flatten" scene.ron --object terrain.ron=- -o scene.raw
  # ThRend reads "..\NAME" (a Windows path: on Linux a file of that name in the working
  # directory) and writes ../results/.
  for f in settings:viewSettings scene.inp:scene.inp materials:materials tsky:tsky colormap:colormap; do
    ln -s "$d/${f%%:*}" "$d/thrend/bin/..\\${f#*:}"
  done
  trace=("$bin/irsig-trace" --scene scene.raw --materials materials.ron --view view.ron)
  fast=(--radiance-exr out/f.radiance.exr --dc-png out/f.dc.png --lut out/f.lut.txt)
  e2e="'$bin/irsig-import' box.obj --materials materials.ron > out/box.ron &&
    '$bin/irsig-import' terrain.obj --materials materials.ron |
    '$bin/irsig-flatten' scene.ron --object terrain.ron=- --object box.ron=out/box.ron |
    '$bin/irsig-trace' --scene - --materials materials.ron --view view.ron --threads 2 -o out/e"

  # Geometry first: the same pixels hit in both.
  "${trace[@]}" -o out/g > /dev/null
  (cd thrend/bin && "$work/build/thrend2" < /dev/null > /dev/null)
  pngtopnm out/g.map.png > out/map.pgm
  pngtopnm thrend/results/real.png > out/real.ppm
  python3 - out/map.pgm out/real.ppm <<'PY'
import sys
def pnm(path):
    data = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    w, h = int(fields[1]), int(fields[2])
    return fields[0], w, h, data[pos + 1:]
kind, w, h, irsig = pnm(sys.argv[1])
assert kind == b"P5", kind
kind, w2, h2, thrend = pnm(sys.argv[2])
assert kind == b"P6" and (w2, h2) == (w, h), (kind, w2, h2)
# irsig: the primary material id (upper nibble): 1 terrain, 2 box, 0 nothing.
a = [v >> 4 for v in irsig]
# ThRend: grey of the surface temperature over 0-100 degC; white where the ray hit nothing.
def cls(g):
    return 0 if g == 255 else (1 if g < 90 else 2)
b = [cls(thrend[3 * k]) for k in range(w * h)]
names = ("nothing", "terrain", "box")
# ThRend's ray of column i starts at the pixel's corner and moves half a pixel's angle more
# (i/w - 1/2, then -1/2 of a pixel): 0.98 of a pixel left of and below irsig's centre ray of the
# same pixel, so ThRend's (i, r) is irsig's (i - 1, r + 1), rows from the top. Best shift too.
def agree(dx, dy):
    same = n = 0
    confusion = {}
    for r in range(2, h - 2):
        for c in range(2, w - 2):
            x, y = a[(r + dy) * w + c + dx], b[r * w + c]
            same += x == y
            n += 1
            confusion[(x, y)] = confusion.get((x, y), 0) + 1
    return same / n, n, confusion
frac, n, conf = agree(-1, 1)
best = max(((agree(dx, dy)[0], dx, dy) for dx in (-2, -1, 0) for dy in (0, 1, 2)))
print("geometry: %.3f %% of %d pixels agree (terrain / box / nothing), ThRend (i, r) against irsig (i-1, r+1);"
      " best shift (%d, %d): %.3f %%" % (100 * frac, n, best[1], best[2], 100 * best[0]))
for (x, y), k in sorted(conf.items()):
    if x != y:
        print("  irsig %s, ThRend %s: %d pixels" % (names[x], names[y], k))
print("  pixels: irsig terrain %d, box %d, nothing %d; ThRend terrain %d, box %d, nothing %d"
      % tuple([a.count(k) for k in (1, 2, 0)] + [b.count(k) for k in (1, 2, 0)]))
PY

  for round in $(seq "$pairs"); do
    (cd thrend/bin && measure "$d/times/thrend1" taskset -c 0 "$work/build/thrend1" < /dev/null)
    measure times/fast1 taskset -c 0 "${trace[@]}" --threads 1 "${fast[@]}"
    measure times/all1 taskset -c 0 "${trace[@]}" --threads 1 -o out/a
    (cd thrend/bin && measure "$d/times/thrend2" "$work/build/thrend2" < /dev/null)
    measure times/fast2 "${trace[@]}" --threads 2 "${fast[@]}"
    measure times/all2 "${trace[@]}" --threads 2 -o out/a
    measure times/e2e bash -c "$e2e"
  done

  echo "${size}x$size, medians of $pairs interleaved rounds (wall s, peak RSS MiB):"
  printf '  %-44s %8s %8s %10s %10s %7s\n' row irsig ThRend "irsig MiB" "ThRend MiB" ratio
  row() {
    local label=$1 mine=$2 theirs=$3
    local t1 t2 m1 m2
    t1=$(cut -d' ' -f1 "times/$mine" | median)
    t2=$(cut -d' ' -f1 "times/$theirs" | median)
    m1=$(cut -d' ' -f2 "times/$mine" | median)
    m2=$(cut -d' ' -f2 "times/$theirs" | median)
    printf '  %-44s %8.2f %8.2f %10.0f %10.0f %7.2f\n' "$label" "$t1" "$t2" "$(echo "$m1 / 1024" | bc -l)" \
      "$(echo "$m2 / 1024" | bc -l)" "$(echo "$t1 / $t2" | bc -l)"
  }
  row "radiance EXR + DC PNG + LUT, 1 thread" fast1 thrend1
  row "radiance EXR + DC PNG + LUT, 2 threads" fast2 thrend2
  row "-o (all outputs), 1 thread" all1 thrend1
  row "-o (all outputs), 2 threads" all2 thrend2
  row "end to end from text (import | flatten | -o)" e2e thrend2
  cd "$repo"
  rm -rf "$d"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
