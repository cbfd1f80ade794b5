# Executables of the report area (included from tools/apps/CMakeLists.txt).
if(TARGET finverse_report)
add_executable(fin-report ${CMAKE_CURRENT_LIST_DIR}/fin-report.cpp)
target_link_libraries(fin-report PRIVATE finverse_report finverse_fem_io finverse_core finverse_warnings)
endif()
