# Sanitizer and fuzzing builds (docs: README "Sanitizers and fuzzing").
#
# STITCHSIM_SANITIZE: a -fsanitize= list (e.g. "address,undefined") added to every target of
# this project and to its links; undefined behaviour aborts (-fno-sanitize-recover), so a
# test that reaches it fails. scripts/sanitize.sh builds build-asan with it.
#
# STITCHSIM_FUZZ: builds the libFuzzer targets of tests/fuzz (clang only) with
# address,undefined; every library gets -fsanitize=fuzzer-no-link for coverage.
# scripts/fuzz.sh builds build-fuzz with it.
set(STITCHSIM_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined")
option(STITCHSIM_FUZZ "Build the libFuzzer targets in tests/fuzz (clang)" OFF)

if(STITCHSIM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "STITCHSIM_FUZZ needs clang (CXX=clang++); got ${CMAKE_CXX_COMPILER_ID}")
  endif()
  if(STITCHSIM_SANITIZE STREQUAL "")
    set(STITCHSIM_SANITIZE "address,undefined")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(NOT STITCHSIM_SANITIZE STREQUAL "")
  add_compile_options(-fsanitize=${STITCHSIM_SANITIZE} -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${STITCHSIM_SANITIZE})
  if(STITCHSIM_SANITIZE MATCHES "undefined")
    add_compile_options(-fno-sanitize-recover=undefined)
    # GCC leaves float-to-int overflow out of "undefined" (clang has it); we want it.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      add_compile_options(-fsanitize=float-cast-overflow -fno-sanitize-recover=float-cast-overflow)
      add_link_options(-fsanitize=float-cast-overflow)
    endif()
  endif()
endif()
