#!/bin/sh
# The speed targets of issues 16 and 20, measured side by side in one run, each with the load
# average before it (the figures mean something only on an otherwise idle machine).
#   bench/speed_targets.sh BUILD_DIR [MESHES_DIR]
# BUILD_DIR: a Release build with -DMEDAX_BUILD_BENCHMARKS=ON (docs/benchmarks.md);
# MESHES_DIR: the mesh corpus with koala (default data/meshes, where bench_qmat and
# bench_coverage_axis read armadillo, fertility, elephant and plane: scripts/fetch-meshes.sh).
set -eu
build=${1:?usage: bench/speed_targets.sh BUILD_DIR [MESHES_DIR]}
meshes=${2:-}
bin=$build/bin
root=$(cd "$(dirname "$0")/.." && pwd)
meshes=${meshes:-$root/data/meshes}

step() { printf '\n== %s   [load average %s]\n' "$1" "$(cut -d' ' -f1-3 /proc/loadavg)"; }

step "issue 16: Delaunay of 1M koala samples, 2 threads (target <= 5 s wall)"
"$bin/bench_delaunay_poisson" --meshes "$meshes" --benchmark_filter='delaunay/1M/threads:2'
step "issue 16: Dey-Zhao at 1M koala samples (target <= 8 s)"
"$bin/bench_dey_zhao" --meshes "$meshes" --benchmark_filter='dey_zhao/1M/iter'
step "issue 16: Poisson-disk sampling, 1M koala samples, 2 threads (target <= 5 s wall; uniform candidates, then darts)"
"$bin/bench_delaunay_poisson" --meshes "$meshes" --benchmark_filter='poisson(_darts)?/1M/threads:2'
step "issue 16: quickstart's reconstruction on spot (target <= 0.6 s; the 'reconstruction' row)"
"$bin/medax" bench "$root/pipelines/quickstart.yaml" --repeat 5
step "issue 20: Q-MAT simplification (target: 5x faster than the authors' times in paper_s)"
"$bin/bench_qmat"
step "issue 20: Coverage Axis exact selection (target: within VMAS Table 2's CA sel times)"
"$bin/bench_coverage_axis" --benchmark_filter=Exact
