#!/usr/bin/env sh
# The README's first command: builds the tools, then runs the quickstart pipeline
# (pipelines/quickstart.ron), which renders a pool, a warm panel, a grass field, a road and
# a car under the US Standard 1976 sky into out/quickstart/. Run from anywhere:
#
#     sh pipelines/quickstart.sh            # extra arguments go to irsig-run (--force, -n)
#
# It says what it is doing before the build, which takes minutes the first time. cargo
# shows its progress bar when standard error is a terminal, and a line per crate it
# compiles when it is a file or a pipe (a log, CI): never minutes of silence.
set -eu
cd "$(dirname "$0")/.."
echo "quickstart: building the tools (cargo build --release): 5-15 minutes the first time, seconds after" >&2
cargo build --release --bins
bin="${CARGO_TARGET_DIR:-target}/release"
"$bin/irsig-run" "$@" pipelines/quickstart.ron
echo "quickstart: out/quickstart/colour.png is the picture, report.html the run report (sensor.exr the radiance, lut.txt the counts)"
