# Stitch planner throughput: stitches/s planning a 1-million-stitch row and a large circle in
# each mode, with the programme written to a discarding stream and without writing.
add_executable(planner_bench ${CMAKE_CURRENT_LIST_DIR}/planner_bench.cpp)
target_compile_options(planner_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(planner_bench PRIVATE
  stitchsim::planner stitchsim::scene stitchsim::program benchmark::benchmark)
