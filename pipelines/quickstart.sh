#!/usr/bin/env sh
# The README's first command: builds the tools, then runs the quickstart pipeline
# (pipelines/quickstart.ron), which renders a pool, a warm panel, a grass field, a road and
# a car under the US Standard 1976 sky into out/quickstart/. Run from anywhere:
#
#     sh pipelines/quickstart.sh            # extra arguments go to irsig-run (--force, -n)
#
# It says what it is doing before the build, which takes minutes the first time: cargo's
# progress is shown when standard error is a terminal, and kept quiet when it is a file or
# a pipe (a log, CI).
set -eu
cd "$(dirname "$0")/.."
echo "quickstart: building the tools (cargo build --release): 5-15 minutes the first time, seconds after" >&2
if [ -t 2 ]; then
  cargo build --release --bins
else
  cargo build --release --bins --quiet
fi
bin="${CARGO_TARGET_DIR:-target}/release"
"$bin/irsig-run" "$@" pipelines/quickstart.ron
echo "quickstart: out/quickstart/colour.png is the picture, report.html the run report (sensor.exr the radiance, lut.txt the counts)"
