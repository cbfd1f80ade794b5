# fin-cfd-bench's DFG 2D-2 comparison with the OpenFOAM peer at two time steps (inputs written by
# the script; no golden file: it checks the reported numbers against the inputs').
if(TARGET fin-cfd-bench)
  add_test(NAME regression_cfd_bench_peer_time_step
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cfd/bench_peer_time_step.sh $<TARGET_FILE:fin-cfd-bench>
                   ${CMAKE_CURRENT_BINARY_DIR}/cfd/bench_peer_time_step)
  set_tests_properties(regression_cfd_bench_peer_time_step PROPERTIES LABELS "regression")
endif()
