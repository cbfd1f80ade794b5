# Executables of the vision area (included from tools/apps/CMakeLists.txt).
add_executable(fin-synth ${CMAKE_CURRENT_LIST_DIR}/fin-synth.cpp)
target_link_libraries(fin-synth PRIVATE finverse_vision_synth finverse_vision finverse_vtkio finverse_core finverse_warnings)

add_executable(fin-track ${CMAKE_CURRENT_LIST_DIR}/fin-track.cpp)
target_link_libraries(fin-track PRIVATE finverse_vision_interop finverse_vision finverse_core finverse_warnings)

add_executable(fin-calibrate ${CMAKE_CURRENT_LIST_DIR}/fin-calibrate.cpp)
target_link_libraries(fin-calibrate PRIVATE finverse_vision_validation finverse_vision_interop finverse_core finverse_warnings)
