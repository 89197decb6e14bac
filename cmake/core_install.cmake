# Install rules of the core and its tools, and the exported CMake package top_sim_core:
#   find_package(top_sim_core REQUIRED)  target_link_libraries(app top_sim::top_sim_core)
install(TARGETS top_sim_core EXPORT top_sim_core_targets
  ARCHIVE DESTINATION ${TOP_SIM_INSTALL_LIB}
  LIBRARY DESTINATION ${TOP_SIM_INSTALL_LIB}
  INCLUDES DESTINATION ${TOP_SIM_INSTALL_INCLUDE})
install(TARGETS top_sim_output top_sim_cli_common ARCHIVE DESTINATION ${TOP_SIM_INSTALL_LIB}
  LIBRARY DESTINATION ${TOP_SIM_INSTALL_LIB})
install(TARGETS top_sim_run top_sim_sweep top_sim_study top_sim_stability RUNTIME DESTINATION ${TOP_SIM_INSTALL_BIN})
if(TARGET top_sim_lcm_echo)
  install(TARGETS top_sim_lcm_echo RUNTIME DESTINATION ${TOP_SIM_INSTALL_BIN})
  if(NOT TOP_SIM_ROS)  # the catkin build installs the library with the node (cmake/ros.cmake)
    install(TARGETS top_sim_lcm LIBRARY DESTINATION ${TOP_SIM_INSTALL_LIB} ARCHIVE DESTINATION ${TOP_SIM_INSTALL_LIB})
  endif()
endif()
install(DIRECTORY include/top_sim/ DESTINATION ${TOP_SIM_INSTALL_INCLUDE}/top_sim)
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
