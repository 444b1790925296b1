#!/bin/sh
# Prints the table "The built-ins between their rows" of docs/accuracy.md: every built-in
# atmosphere's `table` model in 16 sub-bands of 8-14 um against LOWTRAN7 run at observers
# and angles that are rows of no table (the ignored test `sweep` of
# tests/tests/builtin_rows.rs; a few minutes). Run from the repository root:
#
#     sh scripts/atmosphere/sweep.sh
set -eu
IRSIG_LOWTRAN=${IRSIG_LOWTRAN:-$(sh scripts/atmosphere/install-lowtran.sh)}
export IRSIG_LOWTRAN
cargo test --release -q -p irsig-tests --test builtin_rows -- --ignored --exact sweep --nocapture |
    sed -n '/^| /p'
