# Offset curves on a surface (seed 002): offsets per second, the paper's method and the
# corrected one, 790 offsets of 3.81 mm as on the seed's wing.
add_executable(offset_bench ${CMAKE_CURRENT_LIST_DIR}/offset_bench.cpp)
target_compile_options(offset_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(offset_bench PRIVATE stitchsim::planner stitchsim::geom benchmark::benchmark)
