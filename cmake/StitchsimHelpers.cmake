# Warnings are errors in our own code.
set(STITCHSIM_WARNINGS -Wall -Wextra -Wpedantic -Werror)
# GCC 12 reports false -Wrestrict positives inside libstdc++ string concatenation at -O2/-O3
# (GCC bug 105329); the warning stays on, just not as an error.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND STITCHSIM_WARNINGS -Wno-error=restrict -Wno-restrict)
  # In a unity build a source file is included by another, so GCC takes a class of its unnamed
  # namespace used by a class of a header (a pimpl's Impl) for one defined in a header.
  if(STITCHSIM_UNITY_BUILD)
    list(APPEND STITCHSIM_WARNINGS -Wno-subobject-linkage)
  endif()
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

# The compile flags of every test executable, and of the precompiled header they share. Test
# code is built at -O1: the code under test is the libraries', built as configured, and the
# test bodies (mostly calls and comparisons) gain little from -O3 but take twice as long to
# compile. Test sources are not unity-built: each keeps its own unnamed namespace.
function(stitchsim_test_flags name)
  set_target_properties(${name} PROPERTIES UNITY_BUILD OFF)
  target_compile_options(${name} PRIVATE ${STITCHSIM_WARNINGS} $<$<CONFIG:Release>:-O1>)
  # GCC 12 at -O1 reports std::string concatenations of literals as out of bounds (the
  # libstdc++ false positive of GCC bug 105651); the libraries, at -O3, keep the warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${name} PRIVATE -Wno-array-bounds -Wno-stringop-overflow)
  endif()
  target_compile_definitions(${name} PRIVATE
    STITCHSIM_SOURCE_DIR="${STITCHSIM_SOURCE_DIR}"
    STITCHSIM_BINARY_DIR="${CMAKE_BINARY_DIR}")
endfunction()

# stitchsim_add_test(NAME SOURCES ... LINKS ... [CLI]): one GoogleTest executable per test folder,
# discovered by ctest as NAME.<Suite>.<Test>. CLI: its tests run the stitchsim binary.
# Every test fails past STITCHSIM_TEST_TIMEOUT seconds (120; the sanitizer build allows more).
set(STITCHSIM_TEST_TIMEOUT 120 CACHE STRING "Longest a test may run, in seconds")
function(stitchsim_add_test name)
  cmake_parse_arguments(ARG "CLI" "" "SOURCES;LINKS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  stitchsim_test_flags(${name})
  target_link_libraries(${name} PRIVATE ${ARG_LINKS} GTest::gtest GTest::gtest_main)
  # GoogleTest, Eigen, nlohmann-json and the standard library parsed once, in
  # stitchsim_test_pch (tests/CMakeLists.txt).
  target_precompile_headers(${name} REUSE_FROM stitchsim_test_pch)
  if(ARG_CLI)
    add_dependencies(${name} stitchsim)
  endif()
  gtest_discover_tests(${name} TEST_PREFIX "${name}." DISCOVERY_TIMEOUT 60
                       PROPERTIES TIMEOUT ${STITCHSIM_TEST_TIMEOUT})
endfunction()

# stitchsim_label_tests(LABEL TEST...): gives discovered GoogleTest tests (full ctest names) a
# label, e.g. `slow` for those that must stay large; scripts/sanitize.sh leaves `slow` out.
# The label is set when ctest reads the folder, after the discovered tests (TEST_INCLUDE_FILES
# run in order). ctest ignores a name it does not know: the `test_labels` test checks them all.
function(stitchsim_label_tests label)
  # One file per call (named by its list), so two calls in one folder do not overwrite.
  string(MD5 id "${label}:${ARGN}")
  set(file ${CMAKE_CURRENT_BINARY_DIR}/label_${label}_${id}.cmake)
  set(text "")
  foreach(test ${ARGN})
    string(APPEND text "set_tests_properties(\"${test}\" PROPERTIES LABELS ${label})\n")
  endforeach()
  file(WRITE ${file} "${text}")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${file})
  set_property(GLOBAL APPEND PROPERTY STITCHSIM_LABELLED "${label}:${ARGN}")
endfunction()
