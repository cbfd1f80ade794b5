# Executables of the coupled flow-structure area (included from tools/apps/CMakeLists.txt).
if(TARGET finverse_fsi_validation)
  add_executable(fin-fsi ${CMAKE_CURRENT_LIST_DIR}/fin-fsi.cpp)
  target_link_libraries(fin-fsi PRIVATE finverse_fsi_coupled finverse_fsi_validation finverse_core finverse_warnings)
  # fin-fsi fin --materials materials.h5 builds the structure through fin-fit's model factory.
  if(TARGET finverse_fit_fem)
    target_link_libraries(fin-fsi PRIVATE finverse_fit_fem)
    target_compile_definitions(fin-fsi PRIVATE FINVERSE_FSI_HAS_FIT)
  endif()
  if(TARGET finverse_cfd_mpi)
    # fin-fsi fin's flow with its pressure solve over MPI ranks (cfd/parallel/rank_pressure_system.hpp).
    target_link_libraries(fin-fsi PRIVATE finverse_cfd_mpi)
    target_compile_definitions(fin-fsi PRIVATE FINVERSE_HAVE_MPI)
  endif()
  add_executable(fin-fsi-bench ${CMAKE_CURRENT_LIST_DIR}/fin-fsi-bench.cpp)
  target_link_libraries(fin-fsi-bench PRIVATE finverse_fsi_validation finverse_core finverse_warnings)
endif()
