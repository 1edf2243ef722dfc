# Programme text throughput: parse (reader, reader + modal state), write, and the reader's
# memory use on a streamed 1-million-stitch decoupled programme.
add_executable(program_bench ${CMAKE_CURRENT_LIST_DIR}/program_bench.cpp)
target_compile_options(program_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(program_bench PRIVATE stitchsim::program benchmark::benchmark)
