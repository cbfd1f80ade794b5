# Executables of the structural FEM area (included from tools/apps/CMakeLists.txt).
add_executable(fin-fem ${CMAKE_CURRENT_LIST_DIR}/fin-fem.cpp ${CMAKE_CURRENT_LIST_DIR}/fem_file_commands.cpp)
target_link_libraries(fin-fem PRIVATE finverse_fem_validation finverse_fem_io finverse_core finverse_warnings)

add_executable(fin-fem-bench ${CMAKE_CURRENT_LIST_DIR}/fin-fem-bench.cpp)
target_link_libraries(fin-fem-bench PRIVATE finverse_fem_validation finverse_core finverse_warnings)
