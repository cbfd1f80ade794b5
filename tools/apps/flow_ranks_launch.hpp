// fin-cfd fin and fin-fsi fin under an MPI launcher (issue 48): the flow's pressure system over
// the ranks (cfd/parallel/rank_pressure_system.hpp) where built with MPI, else a one-line refusal.
#pragma once

#include <functional>
#include <string>

#include "core/cli.hpp"

#ifdef FINVERSE_HAVE_MPI
#include "cfd/parallel/rank_pressure_system.hpp"
#endif

inline int on_flow_ranks(const std::string& tool, const std::function<int()>& body) {
#ifdef FINVERSE_HAVE_MPI
  return finverse::cfd::run_on_flow_ranks(tool, body);
#else
  finverse::cli::refuse_mpi_launch_without_mpi(tool);
  return body();
#endif
}
