#!/usr/bin/env bash
# Rewrites the parameter block of every docs page from the stages' declarations:
# the lines from `<!-- params: NAME -->` to `<!-- /params -->` become `medax describe NAME --markdown`.
# usage: scripts/update-docs-params.sh [MEDAX_BINARY]   (default build/bin/medax)
set -euo pipefail
cd "$(dirname "$0")/.."
medax=${1:-build/bin/medax}
[ -x "$medax" ] || { echo "no $medax: build first (scripts/build.sh)" >&2; exit 1; }
for page in docs/plugins/*.md examples/*/README.md; do
  grep -q '<!-- params: ' "$page" || continue
  tmp=$(mktemp)
  while IFS= read -r line; do
    if [[ $line =~ ^\<\!--\ params:\ ([a-z0-9_]+)\ --\>$ ]]; then
      "$medax" describe "${BASH_REMATCH[1]}" --markdown
      skipping=1
    elif [[ ${skipping:-0} == 1 ]]; then
      [[ $line == '<!-- /params -->' ]] && skipping=0
    else
      printf '%s\n' "$line"
    fi
  done < "$page" > "$tmp"
  mv "$tmp" "$page"
  echo "updated $page"
done
