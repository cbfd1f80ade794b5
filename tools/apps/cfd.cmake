# CFD executables; included from tools/apps/CMakeLists.txt.
add_executable(fin-poisson-bench ${CMAKE_CURRENT_LIST_DIR}/fin-poisson-bench.cpp)
target_link_libraries(fin-poisson-bench PRIVATE finverse_cfd_validation finverse_cfd finverse_core finverse_warnings)

# The pressure solve on MPI ranks against the threaded solver (issue 48; results/bench/scaling.json).
if(TARGET finverse_cfd_mpi)
  add_executable(fin-poisson-ranks ${CMAKE_CURRENT_LIST_DIR}/fin-poisson-ranks.cpp)
  target_link_libraries(fin-poisson-ranks PRIVATE finverse_cfd_mpi finverse_core CLI11::CLI11 nlohmann_json::nlohmann_json
                        finverse_warnings)
endif()

# The hypre peer of the Poisson benchmark: only where the peers are installed
# (tools/scripts/install-deps.sh --peers); tests never need it.
find_package(MPI COMPONENTS C)
find_path(HYPRE_INCLUDE_DIR HYPRE_struct_ls.h PATH_SUFFIXES hypre)
find_library(HYPRE_LIBRARY HYPRE)
if(MPI_C_FOUND AND HYPRE_INCLUDE_DIR AND HYPRE_LIBRARY)
  # finverse_cfd_hypre: the benchmark problem solved by hypre (tools/cfd/validation/hypre_poisson.hpp).
  add_library(finverse_cfd_hypre ${CMAKE_CURRENT_LIST_DIR}/../cfd/validation/hypre_poisson.cpp)
  target_include_directories(finverse_cfd_hypre SYSTEM PUBLIC ${HYPRE_INCLUDE_DIR})
  # The C API only: keep Open MPI's deprecated C++ bindings out.
  target_compile_definitions(finverse_cfd_hypre PUBLIC OMPI_SKIP_MPICXX MPICH_SKIP_MPICXX)
  target_link_libraries(finverse_cfd_hypre PUBLIC finverse_cfd ${HYPRE_LIBRARY} MPI::MPI_C
                        PRIVATE finverse_cfd_validation finverse_warnings)
  add_executable(fin-poisson-hypre ${CMAKE_CURRENT_LIST_DIR}/fin-poisson-hypre.cpp)
  target_link_libraries(fin-poisson-hypre PRIVATE finverse_cfd_hypre CLI11::CLI11 nlohmann_json::nlohmann_json
                        finverse_warnings)
endif()

# The Navier-Stokes solver's validation cases (rules/cfd.smk).
add_executable(fin-cfd ${CMAKE_CURRENT_LIST_DIR}/fin-cfd.cpp)
target_link_libraries(fin-cfd PRIVATE finverse_cfd_cases finverse_cfd_validation finverse_cfd finverse_cfd_io finverse_core finverse_vtkio finverse_warnings)
if(TARGET finverse_cfd_mpi)
  # fin-cfd fin's pressure solve over MPI ranks (cfd/parallel/rank_pressure_system.hpp).
  target_link_libraries(fin-cfd PRIVATE finverse_cfd_mpi)
  target_compile_definitions(fin-cfd PRIVATE FINVERSE_HAVE_MPI)
endif()

# The flow solver's benchmark file results/bench/cfd.json (rules/bench.smk).
add_executable(fin-cfd-bench ${CMAKE_CURRENT_LIST_DIR}/fin-cfd-bench.cpp)
target_link_libraries(fin-cfd-bench PRIVATE finverse_cfd_validation finverse_cfd finverse_core finverse_warnings)
