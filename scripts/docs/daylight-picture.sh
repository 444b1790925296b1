#!/usr/bin/env sh
# Makes docs/daylight.png, the README's daylight picture: the contact sheet the daylight
# pipeline makes (out/daylight/sheet.png: the quickstart scene at a winter noon in 3-5 um
# and 8-14 um, each by day and without the sun, one grey scale of apparent temperature
# for all four). Builds the tools, then runs pipelines/daylight.ron (LOWTRAN7 must be
# installed: sh scripts/atmosphere/install-lowtran.sh; $IRSIG_LOWTRAN or lowtran7 on
# PATH).
#
#     sh scripts/docs/daylight-picture.sh
#
# tests/tests/daylight.rs checks that the committed picture is what the pipeline makes
# now; run this when that test says it is stale, and check the README's caption still holds.
set -eu
cd "$(dirname "$0")/../.."
cargo build --release --bins --quiet
"${CARGO_TARGET_DIR:-target}/release/irsig-run" pipelines/daylight.ron >/dev/null
cp out/daylight/sheet.png docs/daylight.png
echo "daylight-picture: docs/daylight.png is out/daylight/sheet.png"
