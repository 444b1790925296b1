#!/bin/sh
# Rebuilds rough-surfaces.ron, the library of field-measured rough surfaces, with
# irsig-material fresnel (on PATH, or IRSIG_MATERIAL=path/to/irsig-material). The
# parameters are those examples/fit_rough.rs of irsig-radiometry fits to
# crates/radiometry/data/rough-surfaces.csv; crates/radiometry/tests/rough.rs holds them
# within every measurement. Run from the repository root:
#
#     sh pipelines/materials/generate.sh > pipelines/materials/rough-surfaces.ron
set -eu
tool=${IRSIG_MATERIAL:-irsig-material}
measured="crates/radiometry/data/rough-surfaces.csv"

# entry ID NAME SOURCE ARGS...: one library entry, its source the measurement's citation
# followed by what the tool says it computed. Every table is fitted to 8-14 um
# measurements, and its `band_um` says so, which keeps a tracer from using it in another
# band (the tool writes it itself for an n, k table averaged over its --band).
entry() {
    id=$1 name=$2
    # The citation as a sed replacement: `&`, `|` and `\` taken literally.
    cite=$(printf '%s' "$3" | sed 's/[&|\\]/\\&/g')
    shift 3
    "$tool" fresnel --id "$id" --name "$name" --angles 0:90:1 "$@" |
        sed -n '/^    ($/,/^    ),$/p' |
        sed "s|^      source: \"|      source: \"$cite; |" |
        awk '{ line[NR] = $0 } /^      band_um: /{ has = 1 }
             END { for (i = 1; i <= NR; i++) { print line[i]
                   if (!has && line[i] ~ /^      source: /) print "      band_um: Some((8.0, 14.0))," } }'
}

cat <<'HEAD'
// Rough surfaces fitted to published angular emissivity measurements, 8-14 um. Made by
// pipelines/materials/generate.sh (irsig-material fresnel --roughness); the measurements,
// their sources and stated uncertainties are crates/radiometry/data/rough-surfaces.csv,
// the fit crates/radiometry/examples/fit_rough.rs, and crates/radiometry/tests/rough.rs
// holds every entry within every measured interval. Emissivity tables are (angle from the
// surface normal in degrees, band emissivity), interpolated linearly; `band_um` is their
// band, 8-14 um, and a tracer refuses them in another; docs/accuracy.md ("Rough
// surfaces") says what each rests on.
(
  materials: [
HEAD
entry 1 grass "angular shape: Sobrino & Cuenca (1999, Appl. Opt. 38, 3931), no angular dependence to 65 deg (+-0.01); nadir: Sutherland (1986, J. Atmos. Oceanic Technol. 3, 199), grass 0.97-0.99; fitted n, RMS slope and diffuse reflectance ($measured)" \
    --n 1.20 --roughness 1.5 --diffuse-reflectance 0.0182
entry 2 water "Hale & Querry (1973, Appl. Opt. 12, 555) index, a lightly rippled surface: RMS slope 0.105 fitted to Sobrino & Cuenca (1999, Appl. Opt. 38, 3931), about 7 % below nadir at 65 deg (+-0.01, Rees & James 1992) ($measured)" \
    --nk-table formats/samples/water-hale-querry-nk.txt --band 8-14 --planck-temperature 300 --roughness 0.105 --specular-fraction 1
entry 3 asphalt "not measured at angles: nadir 0.95, typical of published 8-14 um values for dry asphalt (0.93-0.97), not a measurement; angular shape fitted to the gravel of Sobrino & Cuenca (1999, Appl. Opt. 38, 3931), 1-3 % below nadir at 65 deg, a mineral aggregate as asphalt's surface is ($measured)" \
    --n 1.36 --roughness 0.8 --diffuse-reflectance 0.0347
entry 4 concrete "not measured at angles: nadir 0.94, typical of published 8-14 um values for concrete, not a measurement; angular shape fitted to the gravel of Sobrino & Cuenca (1999, Appl. Opt. 38, 3931), 1-3 % below nadir at 65 deg ($measured)" \
    --n 1.36 --roughness 0.8 --diffuse-reflectance 0.0448
entry 5 "soil (clay)" "angular shape: Sobrino & Cuenca (1999, Appl. Opt. 38, 3931), clay 1-3 % below nadir at 65 deg, and Garcia-Santos et al. (2012, J. Geophys. Res. 117, D19116), clayey soils no decrease to 60 deg (+-0.01); nadir: Sutherland (1986), clay 0.96 ($measured)" \
    --n 1.20 --roughness 0.65 --diffuse-reflectance 0.0331
entry 6 sand "angular shape: Sobrino & Cuenca (1999, Appl. Opt. 38, 3931), sand 1-3 % below nadir at 65 deg; nadir: Sutherland (1986, J. Atmos. Oceanic Technol. 3, 199), sands 0.89-0.92 ($measured)" \
    --n 1.36 --roughness 0.8 --diffuse-reflectance 0.0804
entry 7 "matte black paint" "Warren et al. (2019, J. Geophys. Res. Planets 124), Nextel black paint: 0.97 +- 0.01 at 0 deg, 0.89 +- 0.01 at 71 deg ($measured)" \
    --n 1.20 --roughness 0.15 --diffuse-reflectance 0.0219
cat <<'TAIL'
  ],
)
TAIL
