# Ordering the courses of one precedence set (issue 13, S9): our local search and the seed's
# method on 250 and 1,000 courses.
add_executable(sequence_solver_bench ${CMAKE_CURRENT_LIST_DIR}/sequence_solver_bench.cpp)
target_compile_options(sequence_solver_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(sequence_solver_bench PRIVATE stitchsim::planner benchmark::benchmark)
