# Executables of the closing-the-loop area (included from tools/apps/CMakeLists.txt).
add_executable(fin-loop ${CMAKE_CURRENT_LIST_DIR}/fin-loop.cpp)
target_link_libraries(fin-loop PRIVATE finverse_loop_io finverse_loop_flap finverse_core finverse_warnings)
