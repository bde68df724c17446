# Script mode (cmake -DSOURCE=... -DOUT=... -DARCH=... -P write_build_commit.cmake), run at every
# build: writes OUT, a header defining DDAFRAC_COMMIT, the source tree's commit ("-dirty" when
# tracked files differ from it; "unknown" outside a git work tree), and DDAFRAC_ARCH = ARCH. OUT
# is rewritten only when that text changes, so a build recompiles the few files that print it
# only after a commit.
find_package(Git QUIET)
set(commit "unknown")
if(GIT_FOUND)
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE}" rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE head_status ERROR_QUIET)
  if(head_status EQUAL 0 AND head)
    set(commit "${head}")
    execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE}" status --porcelain --untracked-files=no
                    OUTPUT_VARIABLE changes RESULT_VARIABLE status_status ERROR_QUIET)
    if(NOT status_status EQUAL 0 OR changes)
      string(APPEND commit "-dirty")
    endif()
  endif()
endif()
set(text "#pragma once\n// Written at build time by cmake/write_build_commit.cmake.\n#define DDAFRAC_COMMIT \"${commit}\"\n#define DDAFRAC_ARCH \"${ARCH}\"\n")
set(old "")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
