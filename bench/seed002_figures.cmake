# Seed 002's figures beside the paper's (a plain executable; docs/afp.md). Its computations
# (seed002_figures_compute.cpp) are asserted by tests/planner/seed002_figures_test.cpp.
add_executable(seed002_figures ${CMAKE_CURRENT_LIST_DIR}/seed002_figures.cpp
  ${CMAKE_CURRENT_LIST_DIR}/seed002_figures_compute.cpp)
target_compile_options(seed002_figures PRIVATE ${STITCHSIM_WARNINGS})
target_link_libraries(seed002_figures PRIVATE stitchsim::planner stitchsim::scene stitchsim::geom
  stitchsim::common)
