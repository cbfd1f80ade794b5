#!/usr/bin/env bash
# profiles/slurm's bad input (issue 48): a profile that gives a rule several MPI tasks without a
# launcher, or gives them to a rule the workflow does not launch on ranks, is refused by the
# Snakefile (rules/common.smk, check_mpi_resources) in one line naming what to change, exit 2,
# before any job starts; the profile as shipped passes the same dry run. No SLURM needed (-n).
# Usage: run_profile_checks.sh <source dir> <work dir>
set -euo pipefail
src=$1 work=$2
rm -rf "$work" && mkdir -p "$work/run" "$work/profile"
dry() {  # the tiny case's loads stage through the profile in $work/profile, dry
  snakemake results/tiny/loads.h5 -s "$src/Snakefile" -d "$work/run" -n --profile "$work/profile" \
    --configfile "$src/config/cases/tiny.yaml" > "$work/out" 2> "$work/err"
}
cp "$src/profiles/slurm/config.yaml" "$work/profile/config.yaml"
dry || { cat "$work/err"; echo "profiles/slurm as shipped: the dry run failed"; exit 1; }
refused() {  # <name> <expected text>: the dry run exits 2 with one error line saying it
  local rc=0
  dry || rc=$?
  [ $rc = 2 ] && [ "$(grep -c 'error' "$work/err")" = 1 ] && grep -q "$2" "$work/err" ||
    { cat "$work/err"; echo "$1: exit $rc, not one line saying '$2'"; exit 1; }
}
sed -e 's/^  - loads:tasks=1$/  - loads:tasks=2/' -e '/^  - loads:mpi=/d' "$src/profiles/slurm/config.yaml" > "$work/profile/config.yaml"
refused "loads on 2 tasks without mpi" 'loads:tasks=2 without a launcher; add loads:mpi="srun"'
sed -e 's/^  - fit:runtime=720$/  - fit:runtime=720\n  - fit:tasks=3\n  - fit:mpi="srun"/' \
  "$src/profiles/slurm/config.yaml" > "$work/profile/config.yaml"
refused "fit on 3 tasks" "fit:tasks=3, but rule fit is not launched on MPI ranks"
sed -e 's/^  - fsi:tasks=1$/  - fsi:tasks=two/' "$src/profiles/slurm/config.yaml" > "$work/profile/config.yaml"
refused "fsi on 'two' tasks" "fsi:tasks=two, expected a whole number"
echo "workflow_profile_checks: profiles/slurm passes; tasks without a launcher, on the fit, or not a number: exit 2"
