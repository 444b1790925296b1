#!/usr/bin/env sh
# Makes docs/quickstart.png, the README's picture: the sensor's colour preview of the
# quickstart (out/quickstart/colour.png: apparent temperature in the inferno map with its
# scale in kelvin), as the README's first command makes it. Runs that command first
# (pipelines/quickstart.sh: builds the tools, reruns only what is out of date).
#
#     sh scripts/docs/quickstart-picture.sh
#
# tests/tests/quickstart.rs checks that the committed picture is what the quickstart makes
# now; run this when that test says it is stale (after a change to the tracer, the sensor,
# the atmospheres or the quickstart's scene), and check the README's caption still holds.
set -eu
cd "$(dirname "$0")/../.."
sh pipelines/quickstart.sh >/dev/null
cp out/quickstart/colour.png docs/quickstart.png
echo "quickstart-picture: docs/quickstart.png is out/quickstart/colour.png"
