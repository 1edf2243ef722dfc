# Seed 001 at scale: plan the ~1.9-million-stitch wing cover (jump, serpentine) streamed to a
# file and verify it in-process; wall time, stitches/s and RSS per step at half and full span.
add_executable(raster_bench ${CMAKE_CURRENT_LIST_DIR}/raster_bench.cpp)
target_compile_options(raster_bench PRIVATE ${STITCHSIM_WARNINGS})
target_compile_definitions(raster_bench PRIVATE STITCHSIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_link_libraries(raster_bench PRIVATE stitchsim::verify stitchsim::sim stitchsim::planner)
