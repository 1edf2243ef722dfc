# Collision throughput: microseconds per checked pose, full cell with each head, against a
# naive baseline (every pair, no broadphase, objects rebuilt per query).
add_executable(collision_bench ${CMAKE_CURRENT_LIST_DIR}/collision_bench.cpp)
target_compile_options(collision_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(collision_bench PRIVATE
  stitchsim::sim stitchsim::planner benchmark::benchmark)
