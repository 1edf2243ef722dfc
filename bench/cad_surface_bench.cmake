# Point, normal and closest point on an OCCT-backed B-spline surface (near a known point, and
# cold: the grid start and Newton).
add_executable(cad_surface_bench ${CMAKE_CURRENT_LIST_DIR}/cad_surface_bench.cpp)
target_compile_options(cad_surface_bench PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(cad_surface_bench PRIVATE stitchsim::geom benchmark::benchmark)
