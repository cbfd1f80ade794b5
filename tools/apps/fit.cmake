# Executables of the inverse-fit area (included from tools/apps/CMakeLists.txt).
add_executable(fin-fit ${CMAKE_CURRENT_LIST_DIR}/fin-fit.cpp ${CMAKE_CURRENT_LIST_DIR}/fit_file_commands.cpp)
target_link_libraries(fin-fit PRIVATE finverse_fit_io finverse_fit_validation finverse_core finverse_warnings)
add_executable(fin-fit-bench ${CMAKE_CURRENT_LIST_DIR}/fin-fit-bench.cpp)
target_link_libraries(fin-fit-bench PRIVATE finverse_fit_validation finverse_core finverse_warnings)
