#!/usr/bin/env bash
# Regression on real meshes: runs a shipped pipeline on three bundled meshes and compares the
# sha256 of every output file with tests/e2e/hashes/<pipeline>.txt (same config + same seed =
# same bytes; a refactoring must not move them).
# usage: output_hashes.sh MEDAX SOURCE_DIR WORK_DIR PIPELINE [--update]
#   --update rewrites the hash file from this run (do it only for a change you meant, and say
#   why in the commit).
set -euo pipefail
medax=$1 source=$2 work=$3 pipeline=$4 update=${5:-}
expected=$source/tests/e2e/hashes/$pipeline.txt
meshes=("$source/pipelines/meshes/spot.obj" "$source/tests/data/joint.off" "$source/tests/data/ellipsoid.off")

rm -rf "$work"
mkdir -p "$work"
actual=$work/hashes.txt
: > "$actual"
for mesh in "${meshes[@]}"; do
  name=$(basename "${mesh%.*}")
  out=$work/$pipeline-$name
  "$medax" run "$source/pipelines/$pipeline.yaml" --input "$mesh" --out "$out" --quiet > /dev/null \
    || { echo "output_hashes: $pipeline on $name failed (see $out/log.txt)" >&2; exit 1; }
  # Every output but the log, the timings, the completion record (times) and the resolved
  # config (which records paths).
  (cd "$work" && find "$pipeline-$name" -type f ! -name log.txt ! -name timings.json ! -name run.json \
     ! -name config.resolved.yaml \
     | LC_ALL=C sort | xargs sha256sum) >> "$actual"
done

if [ "$update" = "--update" ]; then
  mkdir -p "$(dirname "$expected")"
  cp "$actual" "$expected"
  echo "output_hashes: wrote $expected"
  exit 0
fi
[ -f "$expected" ] || { echo "output_hashes: no $expected; run with --update once" >&2; exit 1; }
if ! diff -u "$expected" "$actual"; then
  echo "output_hashes: $pipeline outputs differ from $expected (runs kept in $work)" >&2
  exit 1
fi
echo "output_hashes: $pipeline: $(wc -l < "$actual") files identical"
