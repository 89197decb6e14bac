# ROS-free tools that reproduce the paper: top_sim_sweep (grid over alpha -> CSV), top_sim_stability.
find_package(Threads REQUIRED)

# The per-point sweep logic lives in the shared CLI library so the paper tests run the same code.
target_sources(top_sim_cli_common PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src/cli/sweep_point.cpp)

add_executable(top_sim_sweep src/cli/top_sim_sweep.cpp)
target_link_libraries(top_sim_sweep top_sim_cli_common Threads::Threads)

# The linear stability of the sleeping state (physics.md section 10): eigenvalues, alpha_c, spin windows.
add_executable(top_sim_stability src/cli/top_sim_stability.cpp)
target_link_libraries(top_sim_stability top_sim_cli_common)
