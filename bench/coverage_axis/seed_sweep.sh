#!/usr/bin/env bash
# Coverage Axis exact selection of the shipped pipeline over seeds: how representative one seed's
# proof is (docs/plugins/coverage_axis.md, "Seeds"). Runs pipelines/coverage_axis.yaml up to the
# coverage_axis stage (repair, normalize, voronoi, coverage_axis), one run at a time, with the
# pipeline's `seed:` replaced, and prints one row per run: model, seed, |M|, proven, LP bound,
# program after presolve (rows x columns), CBC nodes, branch-and-cut wall s, process user+sys CPU s,
# load average at the start.
#
#   bench/coverage_axis/seed_sweep.sh BUILD_DIR                       # seeds 0-4, the four VMAS models
#   SEEDS="0 9" MODELS="fertility.off" bench/coverage_axis/seed_sweep.sh build --set coverage_axis.time_limit=300
set -euo pipefail
build=$1; shift
root=$(cd "$(dirname "$0")/../.." && pwd)
data=${MEDAX_MESHES:-$root/data/meshes}
seeds=${SEEDS:-"0 1 2 3 4"}
models=${MODELS:-"armadillo.off fertility.off elephant.off plane.obj"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for seed in $seeds; do
  sed "s/^seed: .*/seed: $seed/" "$root/pipelines/coverage_axis.yaml" > "$out/seed$seed.yaml"
  for model in $models; do
    run=$out/$model-$seed
    load=$(cut -d' ' -f1 /proc/loadavg)
    /usr/bin/time -f "%U %S" -o "$run.cpu" "$build/bin/medax" run "$out/seed$seed.yaml" --input "$data/$model" \
      --out "$run" --quiet --set qmat.enabled=false --set reconstruction.enabled=false --set counts.enabled=false \
      --set topology.enabled=false "$@" > /dev/null 2>&1 || { echo "$model $seed failed"; continue; }
    python3 - "$run" "$model" "$seed" "$load" <<'PY'
import glob, json, sys
run, model, seed, load = sys.argv[1:]
s = json.load(open(glob.glob(f"{run}/*coverage_axis.json")[0]))
cpu = sum(float(x) for x in open(f"{run}.cpu").read().split()[-2:])
p = s["presolve"]
print(f"{model}\t{seed}\t{s['objective']}\t{'yes' if s['proven_optimal'] else 'no'}\t{s['lp_bound']:.2f}\t"
      f"{p['rows']}x{p['columns']}\t{s['nodes']}\t{s['seconds']['solve']:.2f}\t{cpu:.2f}\t{load}")
PY
  done
done
