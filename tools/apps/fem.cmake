# Executables of the structural FEM area (included from tools/apps/CMakeLists.txt).
add_executable(fin-fem ${CMAKE_CURRENT_LIST_DIR}/fin-fem.cpp)
target_link_libraries(fin-fem PRIVATE finverse_fem_validation finverse_core finverse_warnings)
