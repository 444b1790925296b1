#!/usr/bin/env sh
# Re-records tests/data/golden/outputs.sha256, the bytes tests/tests/golden.rs holds the
# shipped pipelines' outputs to. Run it only for a change meant to alter an output, and say
# in the commit why the bytes changed. Runs the pipelines on a copy of the committed
# pipelines/ with the release tools (built first):
#
#     sh scripts/golden/record.sh
set -eu
cd "$(dirname "$0")/../.."
root=$(pwd)
cargo build --release --bins --quiet
bin="${CARGO_TARGET_DIR:-$root/target}/release"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
git archive HEAD pipelines | tar -x -C "$work"
cd "$work"
for p in quickstart thesis-flyby thesis-experiment quickstart-tiles; do
  "$bin/irsig-run" --quiet --threads 2 "pipelines/$p.ron"
done
# Every file the runs wrote, but the run report (it names irsig's version) and run states.
find out pipelines -type f -newer pipelines/quickstart.ron \
  ! -name report.html ! -path '*/.irsig-run/*' | LC_ALL=C sort | xargs sha256sum \
  > "$root/tests/data/golden/outputs.sha256"
wc -l < "$root/tests/data/golden/outputs.sha256"
