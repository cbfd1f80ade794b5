# CFD executables; included from tools/apps/CMakeLists.txt.
add_executable(fin-poisson-bench ${CMAKE_CURRENT_LIST_DIR}/fin-poisson-bench.cpp)
target_link_libraries(fin-poisson-bench PRIVATE finverse_cfd finverse_core finverse_warnings)
