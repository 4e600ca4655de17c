#!/usr/bin/env bash
# README command 2 (and CI): install the dependencies, build everything, run the whole
# Catch2 suite through ctest, then a short fuzz run of every reader (scripts/fuzz.sh smoke; the
# long campaign is scripts/fuzz.sh campaign).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)" "$@"
scripts/fuzz.sh smoke
