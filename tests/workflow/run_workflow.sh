#!/usr/bin/env bash
# Workflow test: runs the Snakemake DAG on the tiny case in a scratch directory and checks
#  1. a dry run of the default case plans without error,
#  2. the tiny case runs to completion and every summary.json is a valid finverse summary,
#  3. a second run has nothing to do,
#  4. `-R <rule>` reruns that rule only,
#  5. a rebuilt executable (newer mtime) makes its stage rerun.
# Usage: run_workflow.sh <source dir> <build dir>
set -euo pipefail
src=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/finverse_workflow.XXXXXX")
trap 'rm -rf "$work"' EXIT
sm=(snakemake -s "$src/Snakefile" -d "$work" -c2 --config build_dir="$build")

echo "== dry run, default case"
"${sm[@]}" -n --quiet > "$work/dry.log" 2>&1 || { cat "$work/dry.log"; exit 1; }

echo "== tiny case"
"${sm[@]}" --configfile "$src/config/cases/tiny.yaml" > "$work/run1.log" 2>&1 || { cat "$work/run1.log"; exit 1; }
shopt -s nullglob
summaries=("$work"/results/validation/*/summary.json)
echo "summaries: ${#summaries[@]}"
if [ ${#summaries[@]} -gt 0 ]; then
  python3 "$src/tools/scripts/summary.py" --no-fail "${summaries[@]}"
  test -s "$work/results/validation/index.txt"
fi

echo "== rerun: nothing to do"
"${sm[@]}" --configfile "$src/config/cases/tiny.yaml" -n > "$work/run2.log" 2>&1
# Nothing to do, or only the target rule `all` (which has no output of its own).
nothing_to_do() { grep -q "Nothing to be done" "$1" || { grep -qE "^total +1 " "$1" && grep -qE "^all +1 " "$1"; }; }
nothing_to_do "$work/run2.log" || { cat "$work/run2.log"; echo "second run was not empty"; exit 1; }

if [ ${#summaries[@]} -gt 0 ]; then
  echo "== -R validation_index reruns one rule"
  "${sm[@]}" --configfile "$src/config/cases/tiny.yaml" -R validation_index -n > "$work/run3.log" 2>&1
  # The job table lists validation_index once and otherwise only the target rule `all`.
  jobs=$(awk '/^job +count/ {t=1; next} t && /^total/ {exit} t && /^[a-z]/ && $1 != "all" {print $1":"$2}' "$work/run3.log" | tr '\n' ' ')
  [ "$jobs" = "validation_index:1 " ] || { cat "$work/run3.log"; echo "-R validation_index planned: $jobs"; exit 1; }

  echo "== a rebuilt executable reruns its stage"
  case_dir=$(dirname "${summaries[0]}")
  exe=$(grep -o "$build/bin/[a-z-]*" "$work/run1.log" | head -1 || true)
  if [ -n "$exe" ]; then
    cp -p "$exe" "$work/exe.bak"
    touch "$exe"
    "${sm[@]}" --configfile "$src/config/cases/tiny.yaml" -n > "$work/run4.log" 2>&1
    touch -r "$work/exe.bak" "$exe"
    nothing_to_do "$work/run4.log" && { cat "$work/run4.log"; echo "touching $exe did not rerun its stage"; exit 1; }
  fi
fi
echo "workflow test passed"
