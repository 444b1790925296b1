#!/usr/bin/env sh
# The demo job: the stages chained by hand on the sample scene of formats/canonical/
# (two boxes of concrete, steel and skin, one of them mirrored, one with a hot lid),
# through the built-in US Standard 1976 atmosphere (LOWTRAN7, table model), blurred by the
# thesis's 5x5 IFOV. Outputs go to out/demo/. Run from the repository root:
#
#     sh pipelines/demo/run.sh
#
# It builds the tools first. The declarative quickstart pipeline (pipelines/quickstart.ron)
# is not written yet: see issue 6.
set -eu
cargo build --release --bins --quiet
bin="${CARGO_TARGET_DIR:-target}/release"
out=out/demo
samples=formats/canonical/samples
mkdir -p "$out"

# scene + objects -> raw world-space scene (binary)
"$bin/irsig-flatten" "$samples/scene.ron" --materials "$samples/materials.ron" -o "$out/raw.bin"

# raw scene + materials + atmosphere + view -> radiance EXR, truth EXR, maps, DC image, LUT
"$bin/irsig-trace" --scene "$out/raw.bin" --materials "$samples/materials.ron" \
    --view pipelines/demo/view.ron --band 8-14 --atmosphere us-std-1976 -o "$out/demo"

# radiance -> the 1990 5x5 IFOV blur, 8-bit counts at 4 DC/K, LUT, colour preview in kelvin
"$bin/irsig-sensor" "$out/demo.radiance.exr" --mtf box:5x5 --dc-per-kelvin 4 \
    --dc-png "$out/demo.sensor.dc.png" --lut "$out/demo.sensor.lut" \
    --colour-preview "$out/demo.preview.png" -o "$out/demo.sensor.exr"

echo "wrote $out/: demo.radiance.exr demo.truth.exr demo.sensor.exr demo.preview.png ..."
