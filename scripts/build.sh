#!/usr/bin/env bash
# Configures and builds medax (Release) in ./build. Extra arguments are passed to the build,
# e.g. `scripts/build.sh --target medax_cli`.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keys on paths relative to the checkout, so a fresh clone elsewhere reuses the cache.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if [ -f build/CMakeCache.txt ]; then generator=(); fi  # keep the generator the folder was made with
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DMEDAX_BUILD_TESTS=ON
cmake --build build --parallel "$(nproc)" "$@"
