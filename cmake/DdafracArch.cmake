# The processor a build is made for. By default the compiler's portable x86-64 (SSE2): the binary
# runs on any x86-64 machine, and the outputs quoted in docs/ are reproduced bit for bit.
# DDAFRAC_MARCH builds every target for a newer instruction set, e.g. x86-64-v3 (AVX2 and FMA,
# processors from about 2015 on) or native (the building machine's own): faster (Eigen's 6x6
# products use the wider registers and fused multiply-adds), but results differ from a portable
# build in the last digits, and the binary stops with "illegal instruction" on an older
# processor. It applies to the whole project, never to part of it: Eigen's fixed-size types have
# a different alignment under AVX, so libraries built for different instruction sets must not be
# linked together. Results still do not depend on the thread count within one build.
set(DDAFRAC_MARCH "" CACHE STRING
    "instruction set to build for (gcc -march=..., e.g. x86-64-v3 or native); empty: the compiler's portable default")
if(DDAFRAC_MARCH)
  include(CheckCXXCompilerFlag)
  check_cxx_compiler_flag("-march=${DDAFRAC_MARCH}" DDAFRAC_MARCH_SUPPORTED)
  if(NOT DDAFRAC_MARCH_SUPPORTED)
    message(FATAL_ERROR "DDAFRAC_MARCH=${DDAFRAC_MARCH}: the compiler does not accept -march=${DDAFRAC_MARCH} "
                        "(expected an instruction set gcc knows, e.g. x86-64-v3 or native)")
  endif()
  add_compile_options(-march=${DDAFRAC_MARCH})
  set(DDAFRAC_ARCH_TEXT "-march=${DDAFRAC_MARCH}")
else()
  set(DDAFRAC_ARCH_TEXT "portable")
endif()
