# Executables of the mesh area (included from tools/apps/CMakeLists.txt).
add_executable(fin-mesh ${CMAKE_CURRENT_LIST_DIR}/fin-mesh.cpp)
target_link_libraries(fin-mesh PRIVATE finverse_mesh finverse_vtkio finverse_core finverse_warnings)
