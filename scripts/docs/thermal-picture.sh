#!/usr/bin/env sh
# Makes docs/thermal-lwir.png and docs/thermal-mwir.png, the README's thermal pictures: the
# colour previews the thermal pipeline makes (out/thermal/{lwir,mwir}.colour.png: the
# quickstart scene at 14:00 MDT on a summer afternoon, its temperatures from irsig-therm,
# in 8-14 um and 3-5 um). Builds the tools, then runs pipelines/thermal.ron (LOWTRAN7 must
# be installed: sh scripts/atmosphere/install-lowtran.sh; $IRSIG_LOWTRAN or lowtran7 on
# PATH).
#
#     sh scripts/docs/thermal-picture.sh
#
# tests/tests/thermal.rs checks that the committed pictures are what the pipeline makes
# now; run this when that test says they are stale, and check the README's caption still
# holds.
set -eu
cd "$(dirname "$0")/../.."
cargo build --release --bins --quiet
"${CARGO_TARGET_DIR:-target}/release/irsig-run" pipelines/thermal.ron >/dev/null
cp out/thermal/lwir.colour.png docs/thermal-lwir.png
cp out/thermal/mwir.colour.png docs/thermal-mwir.png
echo "thermal-picture: docs/thermal-lwir.png and docs/thermal-mwir.png are the pipeline's colour previews"
