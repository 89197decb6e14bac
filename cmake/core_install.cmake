# Install rules of the core and its tools, and the exported CMake package top_sim_core:
#   find_package(top_sim_core REQUIRED)  target_link_libraries(app top_sim::top_sim_core)
install(TARGETS top_sim_core EXPORT top_sim_core_targets
  ARCHIVE DESTINATION ${TOP_SIM_INSTALL_LIB}
  LIBRARY DESTINATION ${TOP_SIM_INSTALL_LIB}
  INCLUDES DESTINATION ${TOP_SIM_INSTALL_INCLUDE})
install(TARGETS top_sim_output top_sim_studies ARCHIVE DESTINATION ${TOP_SIM_INSTALL_LIB}
  LIBRARY DESTINATION ${TOP_SIM_INSTALL_LIB})
install(TARGETS top_sim_run top_sim_sweep top_sim_study top_sim_stability RUNTIME DESTINATION ${TOP_SIM_INSTALL_BIN})
if(TARGET top_sim_lcm_echo)
  install(TARGETS top_sim_lcm_echo RUNTIME DESTINATION ${TOP_SIM_INSTALL_BIN})
  if(NOT TOP_SIM_ROS)  # the catkin build installs the library with the node (cmake/ros.cmake)
    install(TARGETS top_sim_lcm LIBRARY DESTINATION ${TOP_SIM_INSTALL_LIB} ARCHIVE DESTINATION ${TOP_SIM_INSTALL_LIB})
  endif()
endif()
# The library's public headers, named one by one: a header in include/top_sim is installed only when listed here
# (test instrumentation and internal steppers live in src/core). Each compiles on its own (header_check.cmake).
# What a user of the library calls (the Simulator, scenes, models, states, snapshots, commands, integrators' options,
# the stationary state, stability, fits, pacing, trajectories) and what those headers include; the body's mechanics
# behind the Simulator (shape motion, impacts, flight, energy, orientation, the auto reduction) are internal.
set(TOP_SIM_INSTALLED_HEADERS
  adiabatic.hpp command.hpp command_fields.hpp contact.hpp contact_modes.hpp contact_shapes.hpp cpu_time.hpp
  data_path.hpp dynamics.hpp finite_contact.hpp fit.hpp format.hpp friction.hpp integrators.hpp limits.hpp model.hpp
  pacing.hpp plane.hpp pose.hpp regime.hpp scene.hpp scene_error.hpp simulator.hpp snapshot.hpp stability.hpp
  state.hpp stationary.hpp trajectory.hpp)
list(TRANSFORM TOP_SIM_INSTALLED_HEADERS PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/include/top_sim/
  OUTPUT_VARIABLE top_sim_installed_header_paths)
install(FILES ${top_sim_installed_header_paths} DESTINATION ${TOP_SIM_INSTALL_INCLUDE}/top_sim)
include(${CMAKE_CURRENT_LIST_DIR}/header_check.cmake)
install(DIRECTORY config DESTINATION ${TOP_SIM_INSTALL_SHARE})
# top_sim_stability --plot finds its script at share/top_sim/plots (next to config/).
install(FILES scripts/plots/stability.py scripts/plots/plotlib.py DESTINATION ${TOP_SIM_INSTALL_SHARE}/plots)

include(CMakePackageConfigHelpers)
set(TOP_SIM_CMAKE_DIR ${TOP_SIM_INSTALL_LIB}/cmake/top_sim_core)
install(EXPORT top_sim_core_targets NAMESPACE top_sim:: FILE top_sim_coreTargets.cmake DESTINATION ${TOP_SIM_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/top_sim_coreConfig.cmake.in
  ${PROJECT_BINARY_DIR}/top_sim_coreConfig.cmake INSTALL_DESTINATION ${TOP_SIM_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/top_sim_coreConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/top_sim_coreConfig.cmake ${PROJECT_BINARY_DIR}/top_sim_coreConfigVersion.cmake
  DESTINATION ${TOP_SIM_CMAKE_DIR})
