#!/usr/bin/env bash
# The flow grid's MPI layer (tools/cfd/parallel) on 1, 2, 3 and 4 ranks, oversubscribed on CI's
# two cores: halo exchange, reductions bitwise the serial ones, gather/scatter, a stencil sweep.
# Usage: run_cfd_ranks.sh <cfd_mpi_tests> <mpiexec>
set -euo pipefail
tests=$1 mpiexec=$2
launch=("$mpiexec" --oversubscribe)
[ "$(id -u)" = 0 ] && launch+=(--allow-run-as-root)
for ranks in 1 2 3 4; do
  OMP_NUM_THREADS=1 "${launch[@]}" -np $ranks "$tests" --gtest_brief=1 || { echo "cfd_mpi_tests on $ranks ranks failed"; exit 1; }
done
echo "cfd_mpi_ranks: 1, 2, 3 and 4 ranks pass"
