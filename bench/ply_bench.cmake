# A whole AFP ply planned and its programme written (issue 12, S8): wall time per ply.
add_executable(ply_bench ${CMAKE_CURRENT_LIST_DIR}/ply_bench.cpp)
target_compile_options(ply_bench PRIVATE ${STITCHSIM_WARNINGS})
target_compile_definitions(ply_bench PRIVATE STITCHSIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_link_libraries(ply_bench PRIVATE stitchsim::planner stitchsim::scene)
