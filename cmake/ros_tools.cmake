# ROS tools around the node: keyboard teleop, top_sim_bag, rviz config, screenshot and benchmark scripts.
# Included (optionally) at the end of cmake/ros.cmake, which finds catkin with roscpp, std_msgs, std_srvs
# and generates top_sim's messages; without those this file adds nothing.
if(NOT (roscpp_FOUND AND std_msgs_FOUND AND std_srvs_FOUND))
  message(STATUS "top_sim: roscpp/std_msgs/std_srvs not found by catkin; top_sim_teleop not built")
  return()
endif()

add_executable(top_sim_teleop src/ros/top_sim_teleop.cpp)
# Generated message headers live in the devel space.
# The core's include/ for limits.hpp only (header-only constants: the teleop does not link the core).
target_include_directories(top_sim_teleop PRIVATE ${CATKIN_DEVEL_PREFIX}/include ${catkin_INCLUDE_DIRS}
  ${CMAKE_CURRENT_SOURCE_DIR}/include)
target_link_libraries(top_sim_teleop ${catkin_LIBRARIES})
add_dependencies(top_sim_teleop ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})

install(TARGETS top_sim_teleop RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

# top_sim_bag: a bag's TopStates as top_sim_run's CSV, summary and plot (the rosbag C++ API: librosbag-storage-dev,
# in scripts/lib.sh's package list; record.test runs it).
find_package(rosbag_storage REQUIRED)
add_executable(top_sim_bag src/ros/top_sim_bag.cpp)
target_include_directories(top_sim_bag PRIVATE ${rosbag_storage_INCLUDE_DIRS})
target_link_libraries(top_sim_bag top_sim_ros top_sim_output ${rosbag_storage_LIBRARIES})
install(TARGETS top_sim_bag RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(FILES scripts/plots/trajectory.py DESTINATION ${TOP_SIM_INSTALL_SHARE}/plots)  # plotlib.py: tools.cmake

# rviz/ is installed by ros.cmake; the benchmark and screenshot helpers run from the source tree or installed.
catkin_install_python(PROGRAMS scripts/top_sim_launch scripts/bench_node.py scripts/grab_window.py scripts/rviz_layout.py
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
# bench_node.py imports its helpers from the module beside it.
install(FILES scripts/node_harness.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
