#!/usr/bin/env bash
# README command 1: install the dependencies, build Release, and run the default pipeline
# (normalize -> voronoi -> reconstruction, counts, topology) on the bundled mesh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh --target medax_cli medax_plugins
build/bin/medax run pipelines/quickstart.yaml --out medax-runs/quickstart "$@"
echo
echo "See it: build/bin/medax view medax-runs/quickstart (one HTML page, docs/viewer.md);"
echo "metrics are in medax-runs/quickstart/metrics.json."
