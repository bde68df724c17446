# DDAFRAC_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer on every target, for a
# build in its own directory that proves the memory safety of the tests it runs (issue 13).
# Third-party libraries (gmsh, deal.II) are not instrumented; configure with
# -DDDAFRAC_WITH_FEM=OFF, since deal.II under ASan is slow and not what is being tested.
option(DDAFRAC_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
if(DDAFRAC_SANITIZE OR DDAFRAC_FUZZ)  # a fuzz build (cmake/DdafracFuzz.cmake) needs them too
  # Frame pointers keep the reports' stacks readable; -fno-sanitize-recover makes any UB fatal,
  # so a test cannot pass while the sanitizer complains.
  set(DDAFRAC_SANITIZE_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options(${DDAFRAC_SANITIZE_FLAGS})
  add_link_options(-fsanitize=address,undefined)
  # The tests run with leaks inside gmsh suppressed (ours are still reported) and stop at the
  # first UB report.
  set(DDAFRAC_TEST_ENVIRONMENT
      "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_LIST_DIR}/lsan_suppressions.txt"
      "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
endif()
