#!/usr/bin/env bash
# Docs as tests: every pipeline snippet and every `medax` command line in README.md, docs/ and
# examples/ must still be accepted by medax, so a page cannot drift from the code.
#   - a ```yaml block with a top-level `stages:` is a pipeline (or an experiment): `medax validate`
#     must accept it (with --input when it has no input of its own), saved beside links to
#     pipelines/meshes and pipelines/datasets, so its relative paths resolve as in pipelines/;
#   - a `medax ...` line in a ```sh block runs as `medax validate` (run, bench), or as written
#     (describe, plugins, validate), from the repository root; placeholder meshes (shape.off, ...)
#     become tests/data/ellipsoid.off and the run-only flags are dropped.
# A block or line is left out only when the line before it holds `<!-- docs-test: skip: WHY -->`
# (for a block) or the command's pipeline is a file the page asks the reader to write (listed in
# `user_files` below, each checked as the page's own snippet).
# usage: check_docs.sh MEDAX_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
medax=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
ln -s "$source/pipelines/meshes" "$work/meshes"
ln -s "$source/pipelines/datasets" "$work/datasets"

user_files=" experiment.yaml my.yaml PIPELINE "
placeholder_meshes=" shape.off mesh.off armadillo.off MESH "
mesh=$source/tests/data/ellipsoid.off
failures=0 checked=0

fail() { echo "FAIL $1"; echo "$2" | sed 's/^/    /'; failures=$((failures + 1)); }

# Writes each pipeline snippet of $1 to $work/<page>-<line>.yaml and prints "<file> <line>".
pipeline_snippets() {
  awk -v out="$work/$(echo "${1#$source/}" | tr '/' '_')" '
    /^```yaml/ { if (prev !~ /docs-test: skip/) { inside = 1; start = NR + 1; text = ""; has_stages = 0 }; next }
    inside && /^```/ { inside = 0; if (has_stages) { f = out "-" start ".yaml"; printf "%s", text > f; close(f); print f, start }; next }
    inside { text = text $0 "\n"; if ($0 ~ /^stages:/) has_stages = 1; next }
    { if ($0 !~ /^[[:space:]]*$/) prev = $0 }' "$1"
}

# Prints "<line> <command>" for each medax command line in the ```sh blocks of $1 (a line that
# ends in a backslash continues on the next).
command_lines() {
  awk '
    function emit() { sub(/[[:space:]]+#.*$/, "", command); print start, command; command = "" }
    function take(text) {
      continued = (text ~ /\\[[:space:]]*$/)
      sub(/\\[[:space:]]*$/, "", text)
      command = command text
      if (!continued) emit()
    }
    /^```sh/ { inside = (prev !~ /docs-test: skip/); next }
    /^```/ { inside = 0; next }
    inside && continued { sub(/^[[:space:]]+/, " "); take($0); next }
    inside && /^(MEDAX_PLUGIN_PATH=[^ ]* )?medax / { start = NR; take($0) }
    { if ($0 !~ /^[[:space:]]*$/) prev = $0 }' "$1"
}

# The command to check for a documented one: validate instead of run/bench, real mesh, no run-only flags.
checkable() {
  local -a words out=()
  eval "words=($1)"  # the page's own quoting
  local skip_next=0 w
  for w in "${words[@]}"; do
    if [ $skip_next = 1 ]; then skip_next=0; continue; fi
    case "$w" in
      MEDAX_PLUGIN_PATH=*) continue ;;
      --out|-j|--timeout|--memory-mib|--warmup|--repeat) skip_next=1; continue ;;
      --backend|--partition|--time|--mem|--cpus|--max-parallel|--retry|--poll) skip_next=1; continue ;;
      --quiet|--results-only|--markdown|--no-wait|--view) continue ;;
    esac
    case "$placeholder_meshes" in *" $w "*) w=$mesh ;; esac
    out+=("$w")
  done
  case "${out[1]}" in run|bench) out[1]=validate ;; esac
  printf '%q ' "${out[@]:1}"
}

cd "$source" || exit 1
pages=$(ls README.md docs/*.md docs/plugins/*.md examples/*/README.md 2>/dev/null)
for page in $pages; do
  while read -r file line; do
    [ -n "$file" ] || continue
    checked=$((checked + 1))
    input=()  # a snippet without an input of its own is documented for use with --input
    grep -qE '^(input|inputs|medial_input):' "$file" || input=(--input "$mesh")
    if ! result=$(cd "$work" && "$medax" validate "$file" "${input[@]}" 2>&1); then
      fail "$page:$line: the pipeline snippet is not valid" "$result"
    fi
  done < <(pipeline_snippets "$source/$page")
  while read -r line command; do
    [ -n "$line" ] || continue
    args=$(checkable "$command")
    pipeline=$(eval "set -- $args"; [ "$1" = validate ] && echo "$2")
    if [ -n "$pipeline" ] && case "$user_files" in *" $pipeline "*) true ;; *) false ;; esac; then continue; fi
    checked=$((checked + 1))
    if ! result=$(eval "\"$medax\" $args" 2>&1 < /dev/null); then
      fail "$page:$line: \`$command\` fails (checked as: medax $args)" "$result"
    fi
  done < <(command_lines "$source/$page")
done
echo "docs: $checked snippets and commands checked, $failures failing"
[ $failures -eq 0 ]
