# ddafrac::build_commit: the header <ddafrac/build_commit.hpp> (DDAFRAC_COMMIT, the source commit
# a build was made from, and DDAFRAC_ARCH, the instruction set it was built for), refreshed at
# every build, so that every result file can say which engine wrote it.
set(DDAFRAC_GENERATED_DIR ${CMAKE_BINARY_DIR}/generated)
set(_build_commit_header ${DDAFRAC_GENERATED_DIR}/ddafrac/build_commit.hpp)
add_custom_target(ddafrac_build_commit_header
  COMMAND ${CMAKE_COMMAND} -DSOURCE=${CMAKE_SOURCE_DIR} -DOUT=${_build_commit_header}
          "-DARCH=${DDAFRAC_ARCH_TEXT}"
          -P ${CMAKE_CURRENT_LIST_DIR}/write_build_commit.cmake
  BYPRODUCTS ${_build_commit_header}
  COMMENT "Source commit of this build"
  VERBATIM)
add_library(ddafrac_build_commit INTERFACE)
add_library(ddafrac::build_commit ALIAS ddafrac_build_commit)
target_include_directories(ddafrac_build_commit INTERFACE ${DDAFRAC_GENERATED_DIR})
add_dependencies(ddafrac_build_commit ddafrac_build_commit_header)
