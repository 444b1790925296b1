#!/bin/sh
# Rebuilds materials.ron, the daylight scene's material library: every entry carries its
# emissivity spectrum over 3-5 um and 8-14 um (the tracer averages it over the band it
# traces), from published data, each entry's "source" saying which. Uses
# irsig-material fresnel (on PATH, or IRSIG_MATERIAL=path/to/irsig-material). Run from
# the repository root:
#
#     sh pipelines/daylight/generate.sh > pipelines/daylight/materials.ron
#
# tests/tests/daylight.rs checks that the committed file is what this script makes.
set -eu
tool=${IRSIG_MATERIAL:-irsig-material}
here=pipelines/daylight

# entry ID NAME CITATION SPECTRAL ARGS...: one library entry made by the Fresnel tool, its
# source the citation followed by what the tool says it computed; SPECTRAL, when not
# empty, is a `spectral: ...` line put in place of the tool's (a published spectrum for a
# surface whose angular shape the tool models).
entry() {
    id=$1 name=$2
    # The citation as a sed replacement: `&`, `|` and `\` taken literally.
    cite=$(printf '%s' "$3" | sed 's/[&|\\]/\\&/g')
    spectral=$4
    shift 4
    "$tool" fresnel --id "$id" --name "$name" "$@" |
        sed -n '/^    ($/,/^    ),$/p' |
        sed "s|^      source: \"|      source: \"$cite; |" |
        if [ -n "$spectral" ]; then
            sed "s|^    ),$|      $spectral\n    ),|"
        else
            cat
        fi
}

cat <<'HEAD'
// The daylight scene's materials (pipelines/daylight.ron): the quickstart scene's five
// material ids, each with its emissivity spectrum over both 3-5 um and 8-14 um, so that
// the tracer averages it over whichever band it traces. Made by
// pipelines/daylight/generate.sh; every "source" says where its numbers come from. Where
// no published 3-5 um spectrum of a quickstart material was at hand (the asphalt, the
// panel's matte black paint, the car's glossy paint) another material with one takes its
// id: a clay track, a grey panel, a bare aluminium car (README.md beside this file).
// Emissivity tables are (angle from the surface normal in degrees, emissivity averaged
// over 8-14 um); `band_um` says so.
(
  materials: [
HEAD
# Grass: DIRSIG's grass texture curves are flat beyond 2.9 um; their mean, and the angular
# shape of the rough-surface grass of pipelines/materials/rough-surfaces.ron.
entry 1 grass "spectrum: DIRSIG grass_texture.ems (github.com/Rendered-ai/dirsig-channel @ 135340af, Apache-2.0), whose 43 curves are each constant (to 1e-6) from 2.9 to 28.6 um: their mean 0.953927 there; angular shape: the rough-surface grass of pipelines/materials/rough-surfaces.ron, Sobrino & Cuenca (1999, Appl. Opt. 38, 3931), no angular dependence to 65 deg" \
    "spectral: Some((wavelength_um: [2.9, 28.57], emissivity: [0.953927, 0.953927]))," \
    --angles 0:90:1 --n 1.20 --roughness 1.5 --diffuse-reflectance 0.0182
entry 2 water "Hale & Querry (1973, Appl. Opt. 12, 555) index from 2.65 to 14 um ($here/water-hale-querry-nk.txt), a lightly rippled surface: RMS slope 0.105 fitted to Sobrino & Cuenca (1999, Appl. Opt. 38, 3931) in 8-14 um (crates/radiometry/data/rough-surfaces.csv)" "" \
    --angles 0:90:2 --nk-table "$here/water-hale-querry-nk.txt" --band 8-14 --planck-temperature 300 \
    --roughness 0.105 --specular-fraction 1 |
    # The pond keeps a smooth mirror's glint (no `rms_slope`, so no lobe): the daylight
    # test checks its glint by a mirror's geometry and docs/daylight.png shows it so.
    # Giving it its lobe means redoing both.
    sed '/^      rms_slope: /d'
entry 3 "clay (kaolinite)" "a clay track in the asphalt road's place: kaolinite, Querry (1987, CRDEC-CR-88009) index from 2.5 to 15.2 um ($here/kaolinite-querry-nk.txt), a rough surface of the RMS slope fitted to clay soil in 8-14 um (0.65, crates/radiometry/data/rough-surfaces.csv); no diffuse body, so its emissivity is the index's alone" "" \
    --angles 0:90:5 --nk-table "$here/kaolinite-querry-nk.txt" --band 8-14 --planck-temperature 300 \
    --roughness 0.65
cat <<'PANEL'
    (
      id: 4,
      name: "grey panel",
      emissivity: [(0.0, 0.98), (90.0, 0.98)],
      specular_fraction: 0.0,
      source: "the panel's paint in the daylight scene: DIRSIG background_1.ems (github.com/Rendered-ai/dirsig-channel @ 135340af, Apache-2.0; tests/data/third-party/dirsig-channel/emissivity/background_1.ems), a constant 0.98 from 0.35 to 14.983 um with an angular factor of 1 at every angle; diffuse",
      spectral: Some((wavelength_um: [0.35, 14.983], emissivity: [0.98, 0.98])),
    ),
PANEL
entry 5 aluminium "the car, bare aluminium: Rakic (1995, Appl. Opt. 34, 4755) index of evaporated aluminium films from 2.48 to 15.5 um ($here/aluminium-rakic-nk.txt), a smooth surface; specular fraction 0.5 chosen, not measured (a car body's share of mirror reflection), so that it both mirrors the sky and scatters sunlight" "" \
    --angles 0:90:1 --nk-table "$here/aluminium-rakic-nk.txt" --band 8-14 --planck-temperature 300 \
    --specular-fraction 0.5
cat <<'TAIL'
  ],
)
TAIL
