# Regenerates build/generated/version_info.cpp on every build with the current `git describe`,
# touching the file only when the text changes so an unchanged tree does not relink.
set(FINVERSE_VERSION_CPP ${CMAKE_BINARY_DIR}/generated/version_info.cpp)
add_custom_target(finverse_version_info
  COMMAND ${CMAKE_COMMAND} -DOUT=${FINVERSE_VERSION_CPP} -DSRC=${CMAKE_SOURCE_DIR}
          -DVERSION=${PROJECT_VERSION} -P ${CMAKE_SOURCE_DIR}/cmake/write_version.cmake
  BYPRODUCTS ${FINVERSE_VERSION_CPP}
  COMMENT "finverse version info")
