#!/usr/bin/env bash
# The workflow on SLURM (issue 48): starts a one-node SLURM cluster of its own (slurmctld and
# slurmd on loopback, auth/none, its configuration and state in a scratch directory), runs the tiny
# case's stages up to the fsi stage (fin-synth, fin-track, fin-mesh, fin-cfd fin and fin-fsi fin
# each as a 2-rank MPI job launched by srun, fin-fit) as batch jobs through profiles/slurm, checks
# that each ran as a SLURM job, that the loads and the fsi stage ran on 2 ranks and that the files
# equal the golden files under their tolerances,
# and stops the daemons; nothing is left running. Exit 77 (skipped) without slurm-wlm or root.
# Usage: run_slurm.sh <source dir> <build dir>
set -euo pipefail
src=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)
for d in slurmctld slurmd sbatch srun; do
  command -v "$d" > /dev/null || { echo "$d not found (Debian: slurm-wlm): skipped"; exit 77; }
done
[ "$(id -u)" = 0 ] || { echo "slurmd launches jobs as root here, and this is not root: skipped"; exit 77; }

work=$(mktemp -d "${TMPDIR:-/tmp}/finverse_slurm.XXXXXX")
stop() {
  for p in "$work"/slurmd.pid "$work"/slurmctld.pid; do
    [ -s "$p" ] && kill "$(cat "$p")" 2> /dev/null || true
  done
  sleep 1
  rm -rf "$work"
}
trap stop EXIT

# Two free ports on loopback, so that a cluster already on this machine is not disturbed.
read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
host=$(hostname -s)
mkdir -p "$work"/state "$work"/spool "$work"/tmp
# TmpFS: PMIx makes its per-step directories there; under /tmp they would outlive the test, and
# the next run's step 4.0 (job ids start at 1 again) would find its directory taken and not launch.
# config_overrides: the node's size is taken from here, not measured; memory is not scheduled
# (CR_Core), so the profile's per-stage memory requests fit a small machine.
cat > "$work/slurm.conf" <<CONF
ClusterName=finverse-test
SlurmctldHost=$host(127.0.0.1)
AuthType=auth/none
CredType=cred/none
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
TmpFS=$work/tmp
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
MpiDefault=pmix
ReturnToService=2
NodeName=finverse-node NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=131072 State=UNKNOWN
PartitionName=main Nodes=finverse-node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
export USER=${USER:-$(id -un)}  # Snakemake's SLURM support reads it
slurmctld -c -f "$SLURM_CONF" || { echo "slurmctld did not start: skipped"; exit 77; }
slurmd -N finverse-node -f "$SLURM_CONF" || { echo "slurmd did not start: skipped"; exit 77; }
for _ in $(seq 30); do
  sinfo -h -N -o "%t" 2> /dev/null | grep -qx idle && break
  sleep 1
done
# A machine that cannot host the daemons (no loopback, a locked-down container) says so and
# skips; once the cluster is up, any failure is the profile's or the workflow's.
sinfo -h -N -o "%t" | grep -qx idle ||
  { tail -n 20 "$work"/slurmctld.log "$work"/slurmd.log; echo "no test cluster could be started here: skipped"; exit 77; }

echo "== the tiny case's stages through profiles/slurm, the loads and the fsi stage on 2 ranks"
run=$work/run
mkdir -p "$run" "$work/profile"
# The profile as a site would adapt it: the loads and the fsi stage on 2 tasks of one thread.
# (--set-resources on the command line would replace the profile's whole list, its `mpi` launchers
# included.)
sed -e 's/^  - \(loads\|fsi\):tasks=1$/  - \1:tasks=2/' -e 's/^  - \(loads\|fsi\)=32$/  - \1=1/' \
  "$src/profiles/slurm/config.yaml" > "$work/profile/config.yaml"
for stage in loads fsi; do
  grep -q "^  - $stage:tasks=2$" "$work/profile/config.yaml" && grep -q "^  - $stage=1$" "$work/profile/config.yaml" ||
    { echo "profiles/slurm: no $stage:tasks=1 or $stage=32 line to adapt"; exit 1; }
done
if ! snakemake results/tiny/fsi.h5 -s "$src/Snakefile" -d "$run" --profile "$work/profile" --max-threads "$(nproc)" \
    --configfile "$src/config/cases/tiny.yaml" --config build_dir="$build" > "$work/run.log" 2>&1; then
  cat "$work/run.log" "$run"/results/logs/tiny/{loads,fsi}.log 2> /dev/null
  tail -n 30 "$work"/slurmd.log "$run"/.snakemake/slurm_logs/rule_{loads,fsi}/*.log 2> /dev/null
  echo "snakemake through profiles/slurm failed"; exit 1
fi
for stage in loads fsi; do
  grep -q "pressure solve over 2 MPI ranks" "$run/results/logs/tiny/$stage.log" ||
    { cat "$run/results/logs/tiny/$stage.log"; echo "the $stage stage did not run on 2 MPI ranks"; exit 1; }
done
for rule in synth track mesh loads fit fsi; do
  ls "$run"/.snakemake/slurm_logs/rule_$rule/*.log > /dev/null 2>&1 ||
    { cat "$work/run.log"; echo "rule $rule did not run as a SLURM job"; exit 1; }
done
# The ranks' files are one process's bit for bit (docs/studies/flow_mpi.md), so the threaded
# run's golden files and their tolerances hold.
for golden in vision/tiny_case/kinematics mesh/tiny_case/mesh mesh/tiny_case/motion cfd/tiny_case/loads \
              fit/tiny_case/materials fsi/tiny_case/fsi; do
  dir=$src/tests/regression/$(dirname "$golden") file=$(basename "$golden").h5
  "$build/bin/fin-diff" "$dir/$file" "$run/results/tiny/$file" --tolerances "$dir/tolerances.json" > "$work/diff.log" 2>&1 ||
    { cat "$work/diff.log"; echo "results/tiny/$file from SLURM differs from its golden file"; exit 1; }
done
echo "slurm workflow test passed"
