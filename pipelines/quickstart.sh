#!/usr/bin/env sh
# The README's first command: builds the tools, then runs the quickstart pipeline
# (pipelines/quickstart.ron), which renders a pool, a warm panel, a grass field, a road and
# a car under the US Standard 1976 sky into out/quickstart/. Run from anywhere:
#
#     sh pipelines/quickstart.sh            # extra arguments go to irsig-run (--force, -n)
set -eu
cd "$(dirname "$0")/.."
cargo build --release --bins --quiet
bin="${CARGO_TARGET_DIR:-target}/release"
"$bin/irsig-run" "$@" pipelines/quickstart.ron
echo "quickstart: out/quickstart/colour.png is the picture, report.html the run report (sensor.exr the radiance, lut.txt the counts)"
