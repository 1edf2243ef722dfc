# Kinematics throughput: FK (all links, flange only) and IK (all solutions, SolveIk).
add_executable(kinematics_bench ${CMAKE_CURRENT_LIST_DIR}/kinematics_bench.cpp)
target_compile_options(kinematics_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(kinematics_bench PRIVATE stitchsim::sim benchmark::benchmark)
