#!/usr/bin/env sh
# What calling the tracer from Python costs on top of the command line: the quickstart
# frame (pipelines/quickstart.ron's trace stage, 512 x 384, 8-14 um, US Standard 1976,
# its three files written) through `irsig-trace` and through `irsig.trace`, both release
# builds, alternately, ROUNDS times each (5 unless given); prints each run's wall time and
# the medians. Run by hand (BENCHMARKS.md, "Python"): it builds the release tools and a
# release extension module into a virtual environment of its own (target/py-venv-release).
#
#     sh scripts/bench/python-overhead.sh [ROUNDS]
set -eu
cd "$(dirname "$0")/../.."
rounds="${1:-5}"
target="${CARGO_TARGET_DIR:-target}"
case "$target" in /*) ;; *) target="$PWD/$target" ;; esac
venv="$target/py-venv-release"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check 'maturin>=1.9.4,<2' numpy xarray
# With the package, so that the tools are built with the features maturin builds it with
# (python/Cargo.toml) and the two share every compiled crate.
cargo build --quiet --release -p irsig-flatten -p irsig-trace -p irsig-python
VIRTUAL_ENV="$venv" "$venv/bin/maturin" develop --quiet --release -m python/Cargo.toml
IRSIG_BIN="$target/release" ROUNDS="$rounds" "$venv/bin/python" - <<'PY'
import os, statistics, subprocess, tempfile, time
from pathlib import Path
import irsig

qs = Path("pipelines/quickstart")
bin_ = Path(os.environ["IRSIG_BIN"])
rounds = int(os.environ["ROUNDS"])
options = dict(band="8-14", atmosphere="us-std-1976", atmosphere_model="table")
with tempfile.TemporaryDirectory() as tmp:
    tmp = Path(tmp)
    scene = tmp / "scene.raw"
    irsig.flatten(qs / "scene.ron", materials=qs / "materials.ron", output=scene)
    def outputs(tag):
        return dict(radiance_exr=tmp / f"{tag}.radiance.exr", truth_exr=tmp / f"{tag}.truth.exr",
                    map_png=tmp / f"{tag}.map.png")
    def cli():
        argv = [str(bin_ / "irsig-trace"), "--scene", str(scene), "--materials",
                str(qs / "materials.ron"), "--view", str(qs / "view.ron")]
        for k, v in {**options, **outputs("cli")}.items():
            argv += ["--" + k.replace("_", "-"), str(v)]
        start = time.perf_counter()
        subprocess.run(argv, check=True)
        return time.perf_counter() - start
    def python():
        start = time.perf_counter()
        irsig.trace(scene, qs / "materials.ron", qs / "view.ron", **options, **outputs("py"))
        return time.perf_counter() - start
    cli(); python()   # warm the page cache and the built-in atmosphere's decoding
    times = {"cli": [], "python": []}
    for _ in range(rounds):
        times["cli"].append(cli())
        times["python"].append(python())
    for name in ["radiance.exr", "truth.exr", "map.png"]:
        assert (tmp / f"cli.{name}").read_bytes() == (tmp / f"py.{name}").read_bytes(), name
for k, v in times.items():
    print(f"{k:7} " + " ".join(f"{t:.3f}" for t in v) + f"  median {statistics.median(v):.3f} s")
c, p = statistics.median(times["cli"]), statistics.median(times["python"])
print(f"python overhead: {p - c:+.3f} s, {100 * (p - c) / c:+.1f} % of the command line's frame")
PY
