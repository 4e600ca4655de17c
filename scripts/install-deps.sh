#!/usr/bin/env bash
# Installs medax's build dependencies from Debian (bookworm) with apt-get (nothing when they
# are all present already), then the offline mesh corpus: the CGAL meshes of libcgal-demo,
# checked against datasets/meshes.tsv and copied into data/meshes/ (scripts/fetch-meshes.sh).
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache git pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libtbb-dev libeigen3-dev
  libtet1.5-dev libopenmesh-dev coinor-libcbc-dev libnlopt-cxx-dev
  libyaml-cpp-dev libboost-dev libboost-filesystem-dev
  libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libnanoflann-dev
  catch2 libbenchmark-dev gnuplot-nox
  clang libclang-rt-14-dev
  libopenvdb-dev
  libjs-three chromium libpng-dev
  slurm-wlm munge
  libcgal-demo
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "medax: all build dependencies are installed"
else
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "medax: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

"$(dirname "$0")/fetch-meshes.sh" --debian
