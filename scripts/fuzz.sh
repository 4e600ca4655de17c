#!/usr/bin/env bash
# Fuzzes medax's readers with libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer
# (Debian's clang). Harnesses and seeds: tests/fuzz/.
#
#   scripts/fuzz.sh smoke              each harness 30,000 executions from a fixed seed on its corpus,
#                                      then every kept crasher (CI: the same inputs on every run)
#   scripts/fuzz.sh campaign [N]       N executions per harness (default 1000000)
#   scripts/fuzz.sh campaign N TARGET  one harness only (off obj ply_ascii ply_binary stl ma pipeline xyz)
#
# Builds into build-fuzz. Prints executions, coverage (cov/ft) and peak RSS per harness; a crash
# is saved to build-fuzz/fuzz-findings/<target>/ and makes the script exit 1. Keep a fixed crasher
# in tests/fuzz/regressions/<target>/: test_fuzz_regressions runs it in the normal build.
set -euo pipefail

mode=${1:-smoke}
runs=${2:-1000000}
only=${3:-}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${MEDAX_FUZZ_BUILD:-$root/build-fuzz}
targets=(off obj ply_ascii ply_binary stl ma pipeline xyz)
smoke_runs=${MEDAX_FUZZ_SMOKE_RUNS:-30000}

die() { echo "fuzz.sh: $*" >&2; exit 2; }
case $mode in smoke|campaign) ;; *) die "unknown mode '$mode' (smoke or campaign)";; esac
[[ -z $only || " ${targets[*]} " == *" $only "* ]] || die "unknown target '$only' (${targets[*]})"
[[ -n $only ]] && targets=("$only")

# No silent skip: without clang's libFuzzer runtime the smoke run fails.
command -v clang++ >/dev/null || die "clang++ not found: apt-get install clang libclang-rt-14-dev (or run scripts/install-deps.sh)"
echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, unsigned long) { return 0; }' |
  clang++ -x c++ -fsanitize=fuzzer,address,undefined - -o /tmp/medax-fuzz-probe.$$ 2>/dev/null ||
  die "clang++ cannot link -fsanitize=fuzzer,address,undefined: install libclang-rt-14-dev"
rm -f /tmp/medax-fuzz-probe.$$

flags="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined -fsanitize=fuzzer-no-link"
# The build's output is kept in build-fuzz/build.log and shown when it fails.
mkdir -p "$build"
build_failed() { tail -n 30 "$build/build.log" >&2; die "building the fuzz harnesses failed (whole log: $build/build.log)"; }
cmake -S "$root/tests/fuzz/project" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Fuzz -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$flags" >"$build/build.log" 2>&1 || build_failed
ninja -C "$build" -j "${MEDAX_FUZZ_JOBS:-1}" "${targets[@]/#/fuzz_}" >>"$build/build.log" 2>&1 || build_failed

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
common=(-rss_limit_mb=2048 -max_len=4096 -timeout=10 -print_final_stats=1)
failed=()
printf '%-11s %10s %7s %7s %9s %s\n' target execs cov ft peak_MB result
for t in "${targets[@]}"; do
  work=$build/fuzz-work/$t findings=$build/fuzz-findings/$t
  rm -rf "$work"; mkdir -p "$work" "$findings"
  case $mode in
    # A fixed seed and count make the smoke deterministic: CI cannot turn red on a lucky mutation
    # that a later run would miss; the campaign explores further.
    smoke) budget=(-runs="$smoke_runs" -seed=1) ;;
    campaign) budget=(-runs="$runs") ;;
  esac
  log=$build/fuzz-$t.log
  status=ok
  # New inputs go to the scratch corpus `work`; the seeds in the repo are only read.
  "$build/fuzz/fuzz_$t" "${common[@]}" "${budget[@]}" -artifact_prefix="$findings/" \
    "$work" "$root/tests/fuzz/corpus/$t" >"$log" 2>&1 || status=CRASH
  regressions=("$root"/tests/fuzz/regressions/"$t"/*)
  if [[ -e ${regressions[0]} ]]; then
    "$build/fuzz/fuzz_$t" "${common[@]}" "${regressions[@]}" >>"$log" 2>&1 || status=CRASH
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | head -1 | grep -o '[0-9]*$' || echo ?)
  peak=$(grep -o 'stat::peak_rss_mb: *[0-9]*' "$log" | sort -t: -k4 -n | tail -1 | grep -o '[0-9]*$' || echo ?)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' <<<"$last" | grep -o '[0-9]*' || echo ?)
  ft=$(grep -o 'ft: [0-9]*' <<<"$last" | grep -o '[0-9]*' || echo ?)
  printf '%-11s %10s %7s %7s %9s %s\n' "$t" "$execs" "$cov" "$ft" "$peak" "$status"
  [[ $status == ok ]] || { failed+=("$t"); grep -m3 -E 'ERROR|SUMMARY|runtime error|deadly|uncaught' "$log" >&2 || true; }
done
if (( ${#failed[@]} )); then
  echo "fuzz.sh: findings in ${failed[*]}: logs build-fuzz/fuzz-<target>.log, inputs build-fuzz/fuzz-findings/" >&2
  exit 1
fi
