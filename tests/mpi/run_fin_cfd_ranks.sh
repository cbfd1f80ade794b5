#!/usr/bin/env bash
# fin-cfd fin on 1, 2 and 4 MPI ranks (oversubscribed on CI's two cores) against one process
# (issue 48; tools/cfd/parallel/rank_pressure_system.hpp): the coarse heaving plate as the closed
# body and as the zero-thickness sheet (also 1 rank through the ranks' path,
# FINVERSE_FLOW_RANKS_ON_ONE=1), and the tiny case's fin at h = c/20 (20 steps at CFL 1: the
# ranks' agreement, not the flow, is tested; 4 oversubscribed ranks made it the suite's longest
# run at CFL 0.5). The pressure is all-Neumann here (one singular component); its projections sum
# each x line and then the lines in order, in one process as on the ranks (poisson_operator.cpp's
# component_sums), so loads.h5 must equal one process's bit for bit (fin-diff without tolerances).
# A subcommand that does not run on ranks refuses mpirun in one line, exit 2; so does a rank count
# the grid cannot be split into.
# Usage: run_fin_cfd_ranks.sh <fin-cfd> <fin-diff> <mpiexec> <source dir> <work dir>
set -euo pipefail
cfd=$1 diff=$2 mpiexec=$3 src=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work"
launch=("$mpiexec" --oversubscribe)
[ "$(id -u)" = 0 ] && launch+=(--allow-run-as-root)
"$cfd" --coarse thin_plate --thickness 0.2 --mesh plate_mesh.h5 --motion plate_motion.h5 > plate.log 2>&1
plate=(--mesh plate_mesh.h5 --motion plate_motion.h5 --reynolds 100 --speed 0.1 --periods 0.25 --output-periods 0
       --cells-per-chord 12 --upstream 1.5 --downstream 3 --lateral 1.5 --spanwise 1.5 --stretch-ratio 1.2)
reg=$src/tests/regression/mesh/tiny_case
fin=(--mesh "$reg/mesh.h5" --motion "$reg/motion.h5" --cells-per-chord 20 --cfl 1 --upstream 1.5 --downstream 3
     --lateral 1.5 --spanwise 1.5 --stretch-ratio 1.2)
run_case() {  # name, ranks list, flags...
  local name=$1 ranks=$2
  shift 2
  OMP_NUM_THREADS=1 "$cfd" --threads 1 fin "$@" --out "$name.h5" > "$name.log" 2>&1 ||
    { tail -3 "$name.log"; echo "$name: one process failed"; exit 1; }
  for n in $ranks; do
    # One rank takes the ranks' path only when asked (the scaling benchmark's measurement).
    FINVERSE_FLOW_RANKS_ON_ONE=$([ "$n" = 1 ] && echo 1 || echo 0) OMP_NUM_THREADS=1 \
      "${launch[@]}" -np "$n" "$cfd" --threads 1 fin "$@" --out "$name.ranks$n.h5" > "$name.ranks$n.log" 2>&1 ||
      { tail -5 "$name.ranks$n.log"; echo "$name: $n ranks failed"; exit 1; }
    grep -q "pressure solve over $n MPI ranks" "$name.ranks$n.log" || { echo "$name: $n ranks did not share the solve"; exit 1; }
    "$diff" "$name.h5" "$name.ranks$n.h5" > "$name.ranks$n.diff" 2>&1 ||
      { cat "$name.ranks$n.diff"; echo "$name: $n ranks differ from one process"; exit 1; }
  done
}
run_case plate "2 4" "${plate[@]}"
run_case sheet "1 2" "${plate[@]}" --surface sheet
run_case fin "2 4" "${fin[@]}"
# The sheet's face velocities and convective term are computed on each rank's own lines
# (tools/cfd/flow/rank_lines.cpp); a checkpoint and the flow snapshots written on 2 ranks gather
# the other ranks' lines first, so they are one process's: the snapshots byte for byte, and a
# restart from the ranks' checkpoint in one process gives the uninterrupted run's loads.h5.
one=(env OMP_NUM_THREADS=1 "$cfd" --threads 1 fin "${plate[@]}" --surface sheet)
"${one[@]}" --snapshot-every 5 --out snap.h5 > snap.log 2>&1 || { tail -3 snap.log; echo "sheet snapshots: one process failed"; exit 1; }
ranks2=(env OMP_NUM_THREADS=1 "${launch[@]}" -np 2 "$cfd" --threads 1 fin "${plate[@]}" --surface sheet)
"${ranks2[@]}" --snapshot-every 5 --out snap2.h5 > snap2.log 2>&1 || { tail -5 snap2.log; echo "sheet snapshots: 2 ranks failed"; exit 1; }
"${ranks2[@]}" --checkpoint-every 30 --out ck2.h5 > ck2.log 2>&1 || { tail -5 ck2.log; echo "sheet checkpoint: 2 ranks failed"; exit 1; }
[ "$(ls snap.flow | wc -l)" -ge 2 ] || { ls snap.flow; echo "sheet snapshots: fewer than 2 written"; exit 1; }
for f in snap.flow/*.vtr; do
  b=$(basename "$f")
  cmp -s "$f" "snap2.flow/${b/snap/snap2}" || { echo "sheet snapshot $b on 2 ranks differs from one process's"; exit 1; }
done
"${one[@]}" --restart ck2.checkpoint.h5 --out restarted.h5 > restarted.log 2>&1 ||
  { tail -3 restarted.log; echo "sheet: restart from the 2 ranks' checkpoint failed"; exit 1; }
"$diff" snap.h5 restarted.h5 > restarted.diff 2>&1 ||
  { cat restarted.diff; echo "sheet: restart from the 2 ranks' checkpoint differs from the uninterrupted run"; exit 1; }
# Ranks write nothing but rank 0's files: no checkpoint or snapshot of their own to race on.
[ "$(ls fin.ranks4* | wc -l)" = 3 ] || { ls; echo "fin on 4 ranks: files besides rank 0's"; exit 1; }
# A rank count the grid cannot be split into (16 x 16 lines at c/6, at least 2 per rank and cut
# direction: 11 is prime and needs 22): rank 0's one line naming the largest that works, exit 2,
# and no rank exits before it has said it (FlowRanks::report_once).
rc=0
OMP_NUM_THREADS=1 "${launch[@]}" -np 11 "$cfd" --threads 1 fin "${plate[@]}" --cells-per-chord 6 --lateral 0.5 --spanwise 0.5 \
  --periods 0.05 --out split.h5 > split.out 2> split.err || rc=$?
[ $rc = 2 ] && [ "$(grep -c 'fin-cfd: error:' split.err)" = 1 ] && grep -q "cannot be split into 11 ranks.*use at most 10 ranks" split.err ||
  { cat split.err; echo "fin-cfd on 11 ranks of a 16 x 16-line grid: exit $rc, not one line saying why"; exit 1; }
rc=0
"${launch[@]}" -np 2 "$cfd" --coarse taylor_green > tg.out 2> tg.err || rc=$?
[ $rc = 2 ] && [ "$(grep -c 'fin-cfd: error:' tg.err)" -ge 1 ] && grep -q "does not run on MPI ranks" tg.err ||
  { cat tg.err; echo "fin-cfd taylor_green under mpirun: exit $rc, not one line saying why"; exit 1; }
echo "fin_cfd_mpi_ranks: plate, sheet and fin on 2 and 4 ranks give one process's loads.h5 bit for bit," \
  "the sheet's snapshots and checkpoint too"
