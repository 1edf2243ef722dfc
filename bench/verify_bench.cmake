# End-to-end verification throughput: a decoupled serpentine raster of 10k and 100k stitches,
# written to a file, then executed on the cell and checked by every rule.
add_executable(verify_bench ${CMAKE_CURRENT_LIST_DIR}/verify_bench.cpp)
target_compile_options(verify_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(verify_bench PRIVATE
  stitchsim::verify stitchsim::sim benchmark::benchmark)
