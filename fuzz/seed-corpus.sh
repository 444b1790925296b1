#!/bin/sh
# Seeds fuzz/corpus/<target>/ from the repository's samples and malformed corpora.
# Run from fuzz/ after a release build of irsig-flatten (for a binary raw scene seed):
#   IRSIG_BIN=/path/to/target/release ./seed-corpus.sh
set -eu
root=..
c=corpus
bin=${IRSIG_BIN:-$root/target/release}
for t in object scene material_index view execute ems atm cor dwr rsd rtt obj gltf canonical_ron raw_scene binary_object; do
  mkdir -p "$c/$t"
done
# Legacy targets: the matching files by extension.
for pair in object:fac scene:scn material_index:mat view:view execute:exec ems:ems atm:atm cor:cor dwr:dwr rsd:rsd rtt:rtt; do
  t=${pair%%:*}; ext=${pair#*:}
  cp $root/formats/legacy/samples/*."$ext" $root/tests/data/malformed/legacy/*."$ext" "$c/$t/" 2>/dev/null || true
done
# OBJ, and OBJ + NUL + MTL (the target writes the part after the NUL to m.mtl).
cp $root/formats/canonical/samples/box.obj $root/tests/data/malformed/mesh/*.obj "$c/obj/"
{ sed 's/^mtllib .*/mtllib m.mtl/' $root/formats/canonical/samples/box.obj; printf '\0'; cat $root/formats/canonical/samples/box.mtl; } > "$c/obj/box-with-mtl"
# glTF/GLB: the real third-party files and the malformed ones.
cp $root/tests/data/third-party/webxr-input-profiles/generic-fixed-hand/left.glb "$c/gltf/hand.glb"
cp $root/tests/data/third-party/webxr-input-profiles/generic-trigger/none.glb "$c/gltf/trigger.glb"
cp $root/tests/data/malformed/mesh/*.glb "$c/gltf/"
# Canonical RON: a type byte (see canonical_ron.rs), then the sample.
s=$root/formats/canonical/samples
seed() { { printf "$1"; cat "$2"; } > "$c/canonical_ron/$3"; }
seed '\000' $s/box.ron object
seed '\001' $s/scene.ron scene
seed '\003' $s/materials.ron materials
seed '\004' $s/atmosphere.ron atmosphere
seed '\005' $s/view.ron view
seed '\005' $s/view-look-at.ron view-look-at
seed '\006' $root/formats/samples/pipeline.ron pipeline
for f in $root/tests/data/malformed/scene/*.ron; do seed '\001' "$f" "bad-$(basename "$f")"; done
# Binary forms.
"$bin/irsig-flatten" $s/scene.ron -o "$c/raw_scene/scene.raw"
"$bin/irsig-flatten" $s/scene.ron --ron -o "$c/canonical_ron/raw.tmp"
seed '\002' "$c/canonical_ron/raw.tmp" raw && rm "$c/canonical_ron/raw.tmp"
cp $root/tests/data/object/tri.bin $root/tests/data/malformed/object/*.bin "$c/binary_object/"
"$bin/irsig-import" $s/box.obj --materials $s/materials.ron -o "$c/binary_object/box.bin"
# Radiative-transfer files: the LOWTRAN samples, the third-party decks and tape7s, the
# malformed plans' decks and tape7s, and the quickstart's spectral built-in.
r=$root/tests/data/malformed/radtran
mkdir -p "$c/tape5" "$c/lowtran_tape6" "$c/lowtran_tape7" "$c/modtran_tape7" "$c/spectral_atmosphere"
cp $root/formats/radtran/samples/us-std-1976.tape5 $root/formats/radtran/samples/solar.tape5 $root/tests/data/third-party/lowtran/TAPE5 "$c/tape5/"
for d in $r/*/; do cp "$d/runs/0000.tape5" "$c/tape5/$(basename "$d").tape5"; done
cp $root/formats/radtran/samples/us-std-1976.tape6 $root/formats/radtran/samples/solar.tape6 "$c/lowtran_tape6/"
cp $root/formats/radtran/samples/us-std-1976.tape7 $root/formats/radtran/samples/solar.tape7 "$c/lowtran_tape7/"
for k in truncated column-count repeated-wavenumber falling-wavenumber; do cp "$r/$k/runs/0000.tape7" "$c/lowtran_tape7/$k.tape7"; done
cp $root/tests/data/third-party/pyradi/tape7-* "$r/modtran-column-count/runs/0000.tape7" "$c/modtran_tape7/"
cp $root/formats/radtran/samples/modtran-iemsct3-layout.tape7 "$c/modtran_tape7/"
cp $root/crates/atmosphere/data/us-std-1976.spectral.bin "$c/spectral_atmosphere/"
# The malformed TAPE6 and TAPE7 listings (renamed headers, values out of range, empty and
# cut tables) and binary spectral atmospheres (version 2, counts against the header,
# radiances of 1e38).
for d in $root/tests/data/malformed/lowtran-tape6/*/; do cp "$d/runs/0000.tape6" "$c/lowtran_tape6/$(basename "$d").tape6"; done
for d in $root/tests/data/malformed/lowtran-tape7/*/; do cp "$d/runs/0000.tape7" "$c/lowtran_tape7/$(basename "$d").tape7"; done
cp $root/tests/data/malformed/spectral-binary/*.spa "$c/spectral_atmosphere/"
# Sensor responses, n, k tables, regions files and EXRs: the samples and the malformed cases.
m=$root/tests/data/malformed
mkdir -p "$c/srf" "$c/nk" "$c/regions" "$c/exr_sensor"
cp $root/formats/samples/srf-8-12um.txt $m/srf/*.srf "$c/srf/"
cp $root/formats/samples/water-hale-querry-nk.txt $m/nk/*.nk "$c/nk/"
cp $s/regions.ron "$c/regions/"
cp $root/pipelines/thesis-experiment/regions.ron "$c/regions/thesis-experiment.ron"
for f in $m/regions/*.ron; do cp "$f" "$c/regions/bad-$(basename "$f")"; done
cp $m/base/truth.exr $m/exr-sensor/*.exr "$c/exr_sensor/"
# EXRs that record a band in their provenance: reversed, NaN, missing, another band.
for d in banded-exr banded-exr-report banded-exr-sensor; do cp $m/$d/*.exr "$c/exr_sensor/" 2>/dev/null || true; done
# DIRSIG material sets and curves: the third-party samples.
mkdir -p "$c/dirsig_mat" "$c/dirsig_ems"
cp $root/tests/data/third-party/dirsig-channel/anadirsig.mat "$c/dirsig_mat/"
cp $root/tests/data/third-party/dirsig-channel/emissivity/*.ems "$c/dirsig_ems/"
cp $root/tests/data/malformed/dirsig-mat/therm-*.mat "$c/dirsig_mat/"
mkdir -p "$c/weather"
cp $root/formats/samples/golden-tmy3-aug.epw "$c/weather/"
# Pipeline files: the sample, the runnable pipelines and the malformed cases (the reader
# target); the back-end targets start empty (their input is six arbitrary strings).
mkdir -p "$c/pipeline_reader" "$c/emit_dry_run" "$c/emit_makefile" "$c/emit_slurm"
cp $root/formats/samples/pipeline.ron $root/pipelines/*.ron "$c/pipeline_reader/"
for f in $m/pipeline/*.ron; do cp "$f" "$c/pipeline_reader/bad-$(basename "$f")"; done
