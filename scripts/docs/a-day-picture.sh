#!/usr/bin/env sh
# Makes docs/a-day.png, the README's day in frames: the contact sheet the day pipeline
# makes (out/a-day/contact-sheet.png: the thermal pipeline's scene every hour of 7 August
# at Golden, Colorado, from 00:00 to 23:00 MDT, its temperatures from one irsig-therm run,
# in 8-14 um, every frame through one fixed calibration). Builds the tools, then runs
# pipelines/a-day.ron (no LOWTRAN7 needed: the frames use the built-in atmosphere).
#
#     sh scripts/docs/a-day-picture.sh
#
# Run it when the scene, its materials, the thermal model or the tracer change, and check
# that the README's caption still holds.
set -eu
cd "$(dirname "$0")/../.."
cargo build --release --bins --quiet
"${CARGO_TARGET_DIR:-target}/release/irsig-run" pipelines/a-day.ron >/dev/null
cp out/a-day/contact-sheet.png docs/a-day.png
echo "a-day-picture: docs/a-day.png is the day pipeline's contact sheet"
