#!/bin/sh
# The speed targets of issues 16 and 20 for two builds, alternated (old, new, old, new, ...), then
# one table of every round's figures: how docs/benchmarks.md compares a change with the code before
# it on a machine whose speed drifts between minutes.
#   bench/side_by_side.sh OLD_BUILD NEW_BUILD [ROUNDS] [MESHES_DIR]
# OLD_BUILD, NEW_BUILD: Release builds with -DMEDAX_BUILD_BENCHMARKS=ON (e.g. a worktree of the
# old commit built in its own folder); ROUNDS: 3 by default; MESHES_DIR: as bench/speed_targets.sh.
# The full output of every run goes to side_by_side.log in the current folder.
set -eu
old=${1:?usage: bench/side_by_side.sh OLD_BUILD NEW_BUILD [ROUNDS] [MESHES_DIR]}
new=${2:?usage: bench/side_by_side.sh OLD_BUILD NEW_BUILD [ROUNDS] [MESHES_DIR]}
rounds=${3:-3}
meshes=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
log=side_by_side.log
for build in "$old" "$new"; do
  [ -x "$build/bin/bench_delaunay_poisson" ] || { echo "no benchmarks in $build (configure it with -DMEDAX_BUILD_BENCHMARKS=ON and build it)" >&2; exit 1; }
done

: > "$log"
round=1
while [ "$round" -le "$rounds" ]; do
  for side in old new; do
    if [ "$side" = old ]; then build=$old; else build=$new; fi
    echo "side_by_side: round $round, $side ($build), $(date -u +%H:%M:%S) UTC" >&2
    printf '#### %s %s %s\n' "$side" "$round" "$(date -u +%H:%M:%S)" >> "$log"
    "$here/speed_targets.sh" "$build" $meshes >> "$log" 2>&1
  done
  round=$((round + 1))
done

# One row per figure, one column per side (side_by_side_table.awk).
awk -f "$here/side_by_side_table.awk" "$log"
