#!/usr/bin/env bash
# Workflow test: runs the Snakemake DAG on the tiny case in a scratch directory and checks
#  1. dry runs of the default target (the pipeline only), `validation` and `bench` plan without
#     error, and with nothing built they plan the same jobs (the whole DAG), each missing
#     executable standing as one missing_executable job, which fails with one line saying how to
#     build it,
#  2. the tiny case runs to completion, its stage files (kinematics, mesh, motion, loads,
#     materials, fsi) meet their contracts (fin-contract check) and equal their golden files
#     (tests/regression/<stage>/tiny_case, per-dataset tolerances beside each), its report
#     (fin-report) has index.html, summary.json and the figures, and every summary.json is a
#     valid finverse summary; stage files that disagree are refused by their first common reader,
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
# snakemake <target> in <work dir> with <build dir> [options]: the target comes before the options
# (--config and --configfile take several values and would swallow it).
sm_target() { local target=$1 dir=$2 build_dir=$3; shift 3; snakemake -s "$src/Snakefile" "$target" -d "$dir" -c2 "$@" --config build_dir="$build_dir"; }

# The job table of a dry run, one "rule:count" per line, without missing_executable.
jobs_of() { awk '/^job +count/ {t=1; next} t && /^total/ {exit} t && /^[a-z]/ && $1 != "missing_executable" {print $1":"$2}' "$1"; }

echo "== dry runs: default target, validation, bench"
for target in all validation bench; do
  sm_target "$target" "$work" "$build" -n --quiet > "$work/dry_$target.log" 2>&1 || { cat "$work/dry_$target.log"; exit 1; }
done
# The default target is the pipeline on the default case, no validation case.
if grep -qE "^validation_" "$work/dry_all.log"; then cat "$work/dry_all.log"; echo "the default target plans validation cases"; exit 1; fi
grep -qE "^loads +1 " "$work/dry_all.log" || { cat "$work/dry_all.log"; echo "the default target does not reach loads.h5"; exit 1; }
grep -qE "^fit +1 " "$work/dry_all.log" || { cat "$work/dry_all.log"; echo "the default target does not reach materials.h5"; exit 1; }
grep -qE "^fsi +1 " "$work/dry_all.log" || { cat "$work/dry_all.log"; echo "the default target does not reach fsi.h5"; exit 1; }
grep -qE "^report +1 " "$work/dry_all.log" || { cat "$work/dry_all.log"; echo "the default target does not reach the report"; exit 1; }

echo "== nothing built: the same DAG, and a missing executable says how to build it"
nobuild=$work/nobuild/build
for target in all validation bench; do
  sm_target "$target" "$work/nobuild" "$nobuild" -n --quiet > "$work/nobuild_$target.log" 2>&1 ||
    { cat "$work/nobuild_$target.log"; exit 1; }
  diff <(jobs_of "$work/dry_$target.log") <(jobs_of "$work/nobuild_$target.log") ||
    { echo "nothing built, target $target plans other jobs (< built, > nothing built)"; exit 1; }
done
grep -qE "^missing_executable +[0-9]+ " "$work/nobuild_all.log" || { cat "$work/nobuild_all.log"; exit 1; }
if sm_target results/validation/taylor_green/summary.json "$work/nobuild" "$nobuild" > "$work/nobuild_run.log" 2>&1; then
  cat "$work/nobuild_run.log"; echo "a rule ran without its executable"; exit 1
fi
grep -qE "^[^ ]*/bin/fin-cfd is missing: run cmake -S [^ ]+ -B [^ ]+ -G Ninja && cmake --build " "$work/nobuild_run.log" ||
  { cat "$work/nobuild_run.log"; echo "no line saying how to build fin-cfd"; exit 1; }

echo "== tiny case"
"${sm[@]}" --configfile "$src/config/cases/tiny.yaml" > "$work/run1.log" 2>&1 || { cat "$work/run1.log"; exit 1; }
# One progress line per finished stage, with the ETA (tools/scripts/stage_progress.py).
for stage in synth track mesh loads fit fsi; do
  grep -qE "^finverse: stage [0-9]/7 $stage done in .* so far, about .* left" "$work/run1.log" ||
    { cat "$work/run1.log"; echo "no progress line for stage $stage"; exit 1; }
done
grep -qE "^finverse: stage 7/7 report done in .*; the pipeline is done" "$work/run1.log" ||
  { cat "$work/run1.log"; echo "no progress line for the report"; exit 1; }
for stage in kinematics mesh motion loads materials fsi; do
  "$build/bin/fin-contract" check "$work/results/tiny/$stage.h5" > /dev/null ||
    { echo "results/tiny/$stage.h5 does not meet its contract"; exit 1; }
done
# Every stage file of the tiny case against its golden file (per-dataset tolerances beside it,
# justified in tests/regression/README.md).
for golden in vision/tiny_case/kinematics mesh/tiny_case/mesh mesh/tiny_case/motion cfd/tiny_case/loads \
              fit/tiny_case/materials fsi/tiny_case/fsi; do
  dir=$src/tests/regression/$(dirname "$golden") file=$(basename "$golden").h5
  "$build/bin/fin-diff" "$dir/$file" "$work/results/tiny/$file" --tolerances "$dir/tolerances.json" \
    > "$work/diff_$file.log" 2>&1 || { cat "$work/diff_$file.log"; echo "results/tiny/$file differs from its golden file $dir/$file"; exit 1; }
done
# The report: its page, its scores and the figures of every stage present.
for f in index.html summary.json fig10_pressure_jump.png fig11_moduli.png fig12_root_pitch.png \
         fig14_trailing_edge.png fig15_profiles.png fig16_forces.png; do
  test -s "$work/results/tiny/report/$f" || { echo "results/tiny/report/$f is missing"; exit 1; }
done
python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); assert s["schema"] == "finverse/report" and s["scores"]' \
  "$work/results/tiny/report/summary.json" || { echo "results/tiny/report/summary.json is not a finverse report"; exit 1; }
# The tiny report says, above its scores, that they test the grading and not the method (issue 50).
python3 -c 'import json, sys; assert "not the method" in json.load(open(sys.argv[1])).get("scope", "")' \
  "$work/results/tiny/report/summary.json" || { echo "results/tiny/report/summary.json does not say what its scores test"; exit 1; }
grep -q "Scope:" "$work/results/tiny/report/index.html" || { echo "results/tiny/report/index.html shows no scope"; exit 1; }
# Stages that disagree (issue 33 "Bad input"): a mesh of another fin, a motion of another run; the
# first reader of both files refuses them with one line naming both, exit 2.
t=$work/results/tiny
/usr/bin/python3 - "$t" "$work" <<'PY'
import shutil, sys, h5py
t, work = sys.argv[1:3]
for name in ("mesh", "motion"):
    shutil.copy(f"{t}/{name}.h5", f"{work}/other_{name}.h5")
    with h5py.File(f"{work}/other_{name}.h5", "r+") as f:
        f["points"][...] = f["points"][...] * 1.01
PY
expect_refusal() {  # <log name> <file named in the message> <command...>
  local log=$work/refuse_$1.log named=$2; shift 2
  set +e; "$@" > "$log" 2>&1; local rc=$?; set -e
  [ $rc -eq 2 ] && grep -q "was made from another .*$named" "$log" ||
    { cat "$log"; echo "stages that disagree were not refused (exit $rc): $*"; exit 1; }
}
expect_refusal cfd other_mesh.h5 "$build/bin/fin-cfd" fin --mesh "$work/other_mesh.h5" --motion "$t/motion.h5" --out "$work/x.h5"
expect_refusal fit other_motion.h5 "$build/bin/fin-fit" run --mesh "$t/mesh.h5" --motion "$work/other_motion.h5" \
  --loads "$t/loads.h5" --materials "$src/data/cases/trout_fin_materials.json" --out "$work/x.h5"
expect_refusal report other_mesh.h5 "$build/bin/fin-report" --case x --mesh "$work/other_mesh.h5" --materials "$t/materials.h5" \
  --out-dir "$work/x"
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
