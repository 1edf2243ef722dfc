# The course-ordering solver on public TSPLIB instances with published optima (issue 28; a
# plain executable printing a markdown table; docs/sequence.md).
add_executable(tsplib_bench ${CMAKE_CURRENT_LIST_DIR}/tsplib_bench.cpp)
target_compile_options(tsplib_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(tsplib_bench PRIVATE stitchsim::planner stitchsim::common)
target_compile_definitions(tsplib_bench PRIVATE
  STITCHSIM_TSPLIB_DIR="${CMAKE_CURRENT_LIST_DIR}/data/tsplib")
