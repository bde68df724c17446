# DDAFRAC_FUZZ=ON: libFuzzer targets for the scene parser and the .msh reader (tests/fuzz/),
# for a build in its own directory that feeds them random bytes (issue 13). A fuzz build is a
# sanitizer build too (cmake/DdafracSanitize.cmake), so that a memory error or UB the fuzzer
# reaches stops it at once instead of passing unseen. libFuzzer ships with clang only.
option(DDAFRAC_FUZZ "Build the libFuzzer targets (clang only; implies DDAFRAC_SANITIZE)" OFF)
if(DDAFRAC_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR
      "DDAFRAC_FUZZ=ON needs clang (libFuzzer), not ${CMAKE_CXX_COMPILER_ID}. Configure a fresh "
      "build directory with clang, e.g.\n"
      "  CXX=clang++ cmake -S . -B build-fuzz -DDDAFRAC_FUZZ=ON -DDDAFRAC_WITH_FEM=OFF\n"
      "(Debian 12 packages: clang libclang-rt-14-dev)")
  endif()
  # Coverage feedback for every object of ours; only the fuzz targets link libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
