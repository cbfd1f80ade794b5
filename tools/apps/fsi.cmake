# Executables of the coupled flow-structure area (included from tools/apps/CMakeLists.txt).
if(TARGET finverse_fsi_validation)
  add_executable(fin-fsi ${CMAKE_CURRENT_LIST_DIR}/fin-fsi.cpp)
  target_link_libraries(fin-fsi PRIVATE finverse_fsi_validation finverse_core finverse_warnings)
  add_executable(fin-fsi-bench ${CMAKE_CURRENT_LIST_DIR}/fin-fsi-bench.cpp)
  target_link_libraries(fin-fsi-bench PRIVATE finverse_fsi_validation finverse_core finverse_warnings)
endif()
