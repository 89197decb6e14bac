# ROS-free tools that reproduce the paper: top_sim_sweep (grid over alpha -> CSV), top_sim_stability.
find_package(Threads REQUIRED)

# The per-point sweep logic lives in the shared CLI library (cmake/core.cmake) so the paper tests run the same code.
add_executable(top_sim_sweep src/cli/top_sim_sweep.cpp)
target_link_libraries(top_sim_sweep top_sim_studies Threads::Threads)

# top_sim_fit: friction-law fits (docs/analysis.md). Its --plot script is found in share/top_sim/plots, a link to
# scripts/plots in the build tree as config/ is (cmake/layout.cmake).
add_executable(top_sim_fit src/cli/top_sim_fit.cpp)
target_link_libraries(top_sim_fit top_sim_studies)
if(NOT EXISTS ${TOP_SIM_BUILD_SHARE}/plots)
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/scripts/plots ${TOP_SIM_BUILD_SHARE}/plots SYMBOLIC)
endif()
install(TARGETS top_sim_fit RUNTIME DESTINATION ${TOP_SIM_INSTALL_BIN})
install(FILES scripts/plots/fit_stationary.py scripts/plots/plotlib.py DESTINATION ${TOP_SIM_INSTALL_SHARE}/plots)

# The linear stability of the sleeping state (physics.md section 10): eigenvalues, alpha_c, spin windows.
add_executable(top_sim_stability src/cli/top_sim_stability.cpp)
target_link_libraries(top_sim_stability top_sim_studies nlohmann_json::nlohmann_json)

# Writes src/core/exact_law_table.cpp, the exact drilling law's tables (physics.md section 12); not installed.
add_executable(top_sim_exact_law_table src/cli/top_sim_exact_law_table.cpp)
target_link_libraries(top_sim_exact_law_table top_sim_core)
