#!/usr/bin/env bash
# Issue 22: one VMAS variant (a list of parameter overrides) on the four Table 1 models the corpus
# holds, at the paper's counts, and on other shared meshes at 100 spheres, through
# pipelines/vmas.yaml (unit box, vmas, vmas_dual, reconstruction). Prints one row per mesh:
# mesh, |M|, two-sided Hausdorff distance (% of the diagonal), the vmas stage's seconds.
#
#   bench/vmas/variants.sh BUILD_DIR [--set vmas.key=value ...]
#   MESHES="armadillo.off:83 bunny.obj:100" bench/vmas/variants.sh build ...
#   PIPELINE=pipelines/vmas_samples.yaml bench/vmas/variants.sh build      # the area-sample variant
set -euo pipefail
build=$1; shift
root=$(cd "$(dirname "$0")/../.." && pwd)
data=${MEDAX_MESHES:-/work/shared/data/meshes}
meshes=${MESHES:-"armadillo.off:83 fertility.off:98 elephant.off:117 plane.obj:86 bunny.obj:100 horse.obj:100 hand.obj:100"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for entry in $meshes; do
  mesh=${entry%%:*} count=${entry##*:}
  MEDAX_PLUGIN_PATH= "$build/bin/medax" run "${PIPELINE:-$root/pipelines/vmas.yaml}" --input "$data/$mesh" --out "$out/$mesh" \
    --quiet --set vmas.target_spheres="$count" "$@" > /dev/null 2>&1 || { echo "$mesh failed"; continue; }
  python3 - "$out/$mesh" "$mesh" <<'PY'
import json, sys
run, mesh = sys.argv[1], sys.argv[2]
m = json.load(open(f"{run}/metrics.json"))
t = {s["id"]: s["seconds"] for s in json.load(open(f"{run}/timings.json"))["stages"]}
stalled = " stalled" if "no progress" in open(f"{run}/log.txt").read() else ""
print(f"{mesh}\t{int(m['counts']['vertices'])}\t{m['reconstruction']['hausdorff_pct']:.3f}\t{t['vmas']:.2f}{stalled}")
PY
done
