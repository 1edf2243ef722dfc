# Warnings are errors in our own code.
set(STITCHSIM_WARNINGS -Wall -Wextra -Wpedantic -Werror)
# GCC 12 reports false -Wrestrict positives inside libstdc++ string concatenation at -O2/-O3
# (GCC bug 105329); the warning stays on, just not as an error.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND STITCHSIM_WARNINGS -Wno-error=restrict -Wno-restrict)
endif()

# stitchsim_add_library(NAME SOURCES ... [PUBLIC_LINKS ...] [PRIVATE_LINKS ...])
# Creates stitchsim_<NAME> with alias stitchsim::<NAME>; headers under <folder>/include.
function(stitchsim_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LINKS;PRIVATE_LINKS" ${ARGN})
  add_library(stitchsim_${name} STATIC ${ARG_SOURCES})
  add_library(stitchsim::${name} ALIAS stitchsim_${name})
  target_include_directories(stitchsim_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_compile_options(stitchsim_${name} PRIVATE ${STITCHSIM_WARNINGS})
  target_link_libraries(stitchsim_${name} PUBLIC ${ARG_PUBLIC_LINKS} PRIVATE ${ARG_PRIVATE_LINKS})
endfunction()

# stitchsim_add_test(NAME SOURCES ... LINKS ...): one GoogleTest executable, discovered by ctest.
function(stitchsim_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINKS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_options(${name} PRIVATE ${STITCHSIM_WARNINGS})
  target_link_libraries(${name} PRIVATE ${ARG_LINKS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    STITCHSIM_SOURCE_DIR="${STITCHSIM_SOURCE_DIR}"
    STITCHSIM_BINARY_DIR="${CMAKE_BINARY_DIR}")
  gtest_discover_tests(${name} TEST_PREFIX "${name}." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
endfunction()
