#!/usr/bin/env bash
# Fetches the real meshes of datasets/meshes.tsv into the mesh cache folder and checks each
# file's sha256 against the manifest.
#
#   scripts/fetch-meshes.sh [--debian] [--network] [--dir DIR]
#
#   --debian   the meshes whose source is Debian's libcgal-demo (CGAL's data.tar.gz, CC0), offline;
#              installs libcgal-demo with apt-get when it is missing. This is the default.
#   --network  the others, downloaded with curl from the commit-pinned URLs in the manifest.
#   --dir DIR  the cache folder (default: $MEDAX_DATA_DIR, else <repo>/data/meshes).
#
# Files already present with the right checksum are kept. Exits non-zero, naming each file that
# could not be fetched or whose checksum differs, when any is missing at the end.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
manifest="$repo/datasets/meshes.tsv"
cgal_data_tar=/usr/share/doc/libcgal-dev/data.tar.gz
dest="${MEDAX_DATA_DIR:-$repo/data/meshes}"
want_debian=0
want_network=0

usage() { sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; }

while [ $# -gt 0 ]; do
  case "$1" in
    --debian) want_debian=1 ;;
    --network) want_network=1 ;;
    --dir) dest="$2"; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "fetch-meshes: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done
if [ $want_debian -eq 0 ] && [ $want_network -eq 0 ]; then want_debian=1; fi

failures=()
fetched=0
kept=0

# has_sum FILE SHA256: the file exists and its checksum is the manifest's.
has_sum() { [ -f "$1" ] && [ "$(sha256sum "$1" | cut -d' ' -f1)" = "$2" ]; }

# ensure_libcgal_demo: CGAL's data.tar.gz is on disk, installing libcgal-demo if needed.
ensure_libcgal_demo() {
  [ -f "$cgal_data_tar" ] && return 0
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "fetch-meshes: $cgal_data_tar is missing; installing libcgal-demo with apt-get"
  if ! DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends libcgal-demo; then
    echo "fetch-meshes: could not install libcgal-demo (apt-get failed); install it by hand" \
         "or fetch the meshes with --network" >&2
    return 1
  fi
  [ -f "$cgal_data_tar" ] || { echo "fetch-meshes: libcgal-demo installed but $cgal_data_tar is absent" >&2; return 1; }
}

# from_debian MEMBER OUT: extracts one member of CGAL's data.tar.gz to OUT.
from_debian() { tar -xzf "$cgal_data_tar" -O "$1" > "$2" 2>/dev/null; }

# from_network URL OUT: downloads URL to OUT.
from_network() {
  command -v curl > /dev/null || { echo "fetch-meshes: curl is not installed" >&2; return 1; }
  curl -fsSL --retry 2 --connect-timeout 15 --max-time 300 -o "$2" "$1"
}

# fetch_one NAME SOURCE SHA256: puts NAME in the cache with the right checksum, or records why not.
fetch_one() {
  local name="$1" source="$2" sum="$3"
  local out="$dest/$name"
  if has_sum "$out" "$sum"; then kept=$((kept + 1)); return; fi
  mkdir -p "$(dirname "$out")"
  local tmp="$out.part"
  local ok=0
  case "$source" in
    debian:libcgal-demo:*) from_debian "${source#debian:libcgal-demo:}" "$tmp" && ok=1 ;;
    http*) from_network "$source" "$tmp" && ok=1 ;;
  esac
  if [ $ok -eq 0 ]; then
    rm -f "$tmp"
    failures+=("$name: could not get it from $source")
  elif ! has_sum "$tmp" "$sum"; then
    failures+=("$name: sha256 $(sha256sum "$tmp" | cut -d' ' -f1) differs from the manifest's $sum (kept as $tmp)")
  else
    mv "$tmp" "$out"
    fetched=$((fetched + 1))
  fi
}

[ -f "$manifest" ] || { echo "fetch-meshes: no manifest at $manifest" >&2; exit 1; }
if [ $want_debian -eq 1 ] && ! ensure_libcgal_demo; then
  echo "fetch-meshes: skipping the Debian meshes" >&2
  want_debian=0
  failures+=("the Debian meshes: libcgal-demo is not available")
fi

while IFS=$'\t' read -r name category source licence sum _rest; do
  case "$name" in ''|'#'*|name) continue ;; esac
  case "$source" in
    debian:*) if [ $want_debian -eq 1 ]; then fetch_one "$name" "$source" "$sum"; fi ;;
    *) if [ $want_network -eq 1 ]; then fetch_one "$name" "$source" "$sum"; fi ;;
  esac
done < "$manifest"

echo "fetch-meshes: $fetched fetched, $kept already present, in $dest"
if [ ${#failures[@]} -gt 0 ]; then
  printf 'fetch-meshes: FAILED %s\n' "${failures[@]}" >&2
  if [ $want_network -eq 1 ]; then
    echo "fetch-meshes: downloads need network access to raw.githubusercontent.com" >&2
  fi
  exit 1
fi
