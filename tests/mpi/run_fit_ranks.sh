#!/usr/bin/env bash
# fin-fit run threaded, then under mpirun on 1 and 3 ranks: materials.h5 byte-identical (the
# evaluations are pure functions of their vectors, placed by index; tools/fit/rank_pool.hpp). A
# few seconds each: the tiny case's golden files, a short GA on the linearised increment, a polish.
# Usage: run_fit_ranks.sh <fin-fit> <mpiexec> <source dir> <work dir>
set -euo pipefail
fit=$1 mpiexec=$2 src=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
reg=$src/tests/regression
problem=(--mesh "$reg/mesh/tiny_case/mesh.h5" --motion "$reg/mesh/tiny_case/motion.h5"
         --loads "$reg/cfd/tiny_case/loads.h5" --materials "$src/data/cases/trout_fin_materials.json"
         --objective quasi_static --base stress_free --instant-count 2)
args=(--threads 2 run "${problem[@]}" --increment linear --runs 1 --population 8 --generations 2
      --polish-evaluations 30 --seed 1 --out materials.h5)
# Open MPI refuses root unless told, and more ranks than cores unless told.
launch=("$mpiexec" --oversubscribe)
[ "$(id -u)" = 0 ] && launch+=(--allow-run-as-root)
mkdir "$work/threads" && (cd "$work/threads" && "$fit" "${args[@]}" 2> log) || { cat "$work/threads/log"; exit 1; }
for ranks in 1 3; do
  dir=$work/ranks$ranks
  mkdir "$dir"
  (cd "$dir" && "${launch[@]}" -np $ranks "$fit" "${args[@]}" 2> log) || { cat "$dir/log"; echo "$ranks ranks: failed"; exit 1; }
  cmp "$work/threads/materials.h5" "$dir/materials.h5" || { echo "$ranks ranks: materials.h5 differs from the threaded run's"; exit 1; }
done
grep -q "evaluations per rank in batches: [0-9]* [1-9][0-9]* [1-9][0-9]*" "$work/ranks3/log" ||
  { cat "$work/ranks3/log"; echo "3 ranks: the serving ranks evaluated nothing"; exit 1; }
# A subcommand that does not distribute its evaluations refuses the launcher: one line, exit 2.
rc=0
(cd "$work" && "${launch[@]}" -np 2 "$fit" evaluate "${problem[@]}" > out 2> err) || rc=$?
[ $rc -ne 0 ] || { echo "fin-fit evaluate under mpirun: exit 0"; exit 1; }
[ "$(grep -c 'fin-fit: error:' "$work/err")" = 1 ] && grep -q "only fin-fit run spreads its evaluations" "$work/err" ||
  { cat "$work/err"; echo "fin-fit evaluate under mpirun: not one line saying why"; exit 1; }
echo "fit_mpi_ranks: threaded, 1 and 3 ranks give the same materials.h5"
