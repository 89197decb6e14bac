# The ROS node, messages, dynamic_reconfigure and rostests (included after the core targets exist).
find_package(catkin REQUIRED COMPONENTS
  roscpp std_msgs std_srvs geometry_msgs nav_msgs visualization_msgs rosgraph_msgs
  tf2 tf2_ros tf2_msgs diagnostic_updater dynamic_reconfigure message_generation roslib)

# The Python package top_sim (setup.py): its sources next to the generated top_sim.msg and top_sim._core.
catkin_python_setup()

add_message_files(DIRECTORY msg FILES TopState.msg TopCommand.msg TopStateArray.msg)
add_service_files(DIRECTORY srv FILES Spawn.srv Kill.srv ListTops.srv)
generate_messages(DEPENDENCIES std_msgs geometry_msgs)
generate_dynamic_reconfigure_options(cfg/TopSim.cfg)

catkin_package(
  INCLUDE_DIRS include
  LIBRARIES top_sim_core
  CATKIN_DEPENDS message_runtime roscpp std_msgs std_srvs geometry_msgs nav_msgs visualization_msgs
                 rosgraph_msgs tf2 tf2_ros tf2_msgs diagnostic_updater dynamic_reconfigure roslib)

# The node's parts (docs/architecture.md, "The ROS node"), shared by the node and its unit tests.
add_library(top_sim_ros src/ros/conversions.cpp src/ros/param_yaml.cpp src/ros/node_parameters.cpp
  src/ros/top_input.cpp src/ros/node_top.cpp src/ros/top_set.cpp src/ros/state_output.cpp
  src/ros/node_diagnostics.cpp src/ros/node_reconfigure.cpp src/ros/top_mesh.cpp src/ros/markers.cpp
  src/ros/trail.cpp src/ros/marker_stream.cpp src/ros/cpu_affinity.cpp src/ros/topic_opener.cpp)
target_include_directories(top_sim_ros PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/src/ros ${catkin_INCLUDE_DIRS})
target_link_libraries(top_sim_ros PUBLIC top_sim_core ${catkin_LIBRARIES} yaml-cpp)
add_dependencies(top_sim_ros ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_gencfg)

if(TARGET top_sim_lcm)
  target_link_libraries(top_sim_ros PUBLIC top_sim_lcm)
  install(TARGETS top_sim_lcm
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
endif()

add_executable(top_sim_node src/ros/top_sim_node.cpp)
target_link_libraries(top_sim_node top_sim_ros ${catkin_LIBRARIES})
add_dependencies(top_sim_node ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_gencfg)

install(TARGETS top_sim_ros top_sim_node
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY launch lcm DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})

# The rviz control panel (docs/ros.md, "Control in rviz"): its Qt-free logic and the rviz plugin (librviz-dev).
find_package(rviz REQUIRED)
find_package(pluginlib REQUIRED)
find_package(Qt5 REQUIRED COMPONENTS Widgets)
add_library(top_sim_panel_logic src/rviz/panel_logic.cpp)
target_include_directories(top_sim_panel_logic PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/src/rviz)
target_link_libraries(top_sim_panel_logic PUBLIC top_sim_ros)
add_library(top_sim_rviz src/rviz/control_panel.cpp src/rviz/control_panel.hpp)
set_target_properties(top_sim_rviz PROPERTIES AUTOMOC ON)
target_include_directories(top_sim_rviz PUBLIC ${rviz_INCLUDE_DIRS} ${pluginlib_INCLUDE_DIRS})
target_link_libraries(top_sim_rviz top_sim_panel_logic ${rviz_LIBRARIES} ${pluginlib_LIBRARIES} Qt5::Widgets)
# Interactive markers for every top (a ring tilts the plane, a handle sets the spin, a menu): its own node.
find_package(interactive_markers REQUIRED)
add_executable(trail_bench bench/ros/trail_bench.cpp)  # what a trail add costs (docs/node_benchmark.md)
target_link_libraries(trail_bench top_sim_ros)

add_executable(top_sim_interactive src/rviz/top_sim_interactive.cpp)
target_include_directories(top_sim_interactive PRIVATE ${interactive_markers_INCLUDE_DIRS} ${CMAKE_CURRENT_SOURCE_DIR}/src/ros)
target_link_libraries(top_sim_interactive top_sim_panel_logic ${interactive_markers_LIBRARIES})
install(TARGETS top_sim_interactive RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS top_sim_panel_logic top_sim_rviz
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION} LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(FILES plugin_description.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(DIRECTORY rviz DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION} OPTIONAL)

# rostests of the node (test/ros/*.test) and unit tests of its message maps.
if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  find_package(tf2_msgs REQUIRED)
  catkin_add_gtest(top_sim_ros_unit_tests test/ros/test_conversions.cpp test/ros/test_node_parts.cpp
    test/ros/test_panel_logic.cpp)
  if(TARGET top_sim_ros_unit_tests)
    target_link_libraries(top_sim_ros_unit_tests top_sim_ros top_sim_panel_logic)
    target_compile_definitions(top_sim_ros_unit_tests PRIVATE
      TOP_SIM_TEST_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config")
  endif()
  add_rostest_gtest(top_sim_node_test test/ros/node.test test/ros/test_node.cpp)
  target_link_libraries(top_sim_node_test ${catkin_LIBRARIES})
  target_include_directories(top_sim_node_test PRIVATE ${catkin_INCLUDE_DIRS} ${tf2_msgs_INCLUDE_DIRS})
  add_dependencies(top_sim_node_test top_sim_node ${PROJECT_NAME}_generate_messages_cpp)
  add_rostest(test/ros/hztest.test DEPENDENCIES top_sim_node)
  add_rostest_gtest(top_sim_rate_test test/ros/hztest_1khz.test test/ros/test_rate.cpp)
  target_link_libraries(top_sim_rate_test ${catkin_LIBRARIES})
  target_include_directories(top_sim_rate_test PRIVATE ${catkin_INCLUDE_DIRS})
  add_dependencies(top_sim_rate_test top_sim_node ${PROJECT_NAME}_generate_messages_cpp)
  # Pacing: a stiff command and a too-costly scene keep the rate, services answer, falling behind is reported.
  add_rostest_gtest(top_sim_pacing_test test/ros/pacing_coulomb.test test/ros/test_pacing.cpp)
  target_link_libraries(top_sim_pacing_test ${catkin_LIBRARIES})
  target_include_directories(top_sim_pacing_test PRIVATE ${catkin_INCLUDE_DIRS})
  add_dependencies(top_sim_pacing_test top_sim_node ${PROJECT_NAME}_generate_messages_cpp)
  add_rostest(test/ros/pacing_slow.test DEPENDENCIES top_sim_pacing_test)
  add_rostest(test/ros/phi.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/geometric_phase.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  # The recorded bag through top_sim_bag (cmake/ros_tools.cmake) against top_sim_run, and fitted by top_sim_fit.
  add_rostest(test/ros/record.test DEPENDENCIES top_sim_node top_sim_bag top_sim_run top_sim_fit
              ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/start_errors.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/scene_names.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/tops.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  # ~tops/command, ~per_top_topics both ways, the batch spawn (issue 49).
  add_rostest(test/ros/tops_command.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/background_topics.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/markers.test DEPENDENCIES top_sim_node)
  add_rostest(test/ros/disc_end.test DEPENDENCIES top_sim_node)
  add_rostest(test/ros/bandwidth.test DEPENDENCIES top_sim_node)
  add_rostest(test/ros/interactive.test DEPENDENCIES top_sim_node top_sim_interactive ${PROJECT_NAME}_generate_messages_py)
  # rviz itself under its own Xvfb: every exit on SIGINT is 0 (issue 46)
  add_rostest(test/ros/rviz_shutdown.test DEPENDENCIES top_sim_node top_sim_interactive top_sim_rviz)
  add_rostest_gtest(top_sim_panel_test test/ros/panel.test test/ros/test_panel_widget.cpp)
  find_package(Qt5 REQUIRED COMPONENTS Test)
  target_link_libraries(top_sim_panel_test top_sim_rviz ${catkin_LIBRARIES} Qt5::Test)
  add_dependencies(top_sim_panel_test top_sim_node ${PROJECT_NAME}_generate_messages_cpp)
  add_rostest(test/ros/docs_commands.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/reset_start.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  # Two hosts as network namespaces on one master (docs/ros.md Distribution); one skipped case without root.
  # Its own timeout: the script stops and removes what it started on TERM.
  set(_netns_result ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/netns-distributed.xml)
  catkin_run_tests_target(netns distributed netns-distributed.xml
    COMMAND "timeout -k 15 58 bash ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/distributed_netns.sh ${_netns_result} ${CATKIN_DEVEL_PREFIX}/.."
    DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  # The Python package top_sim of the devel space: top_sim.msg, the physics and python3 -m top_sim.sweep.
  set(_python_package_result ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/python-package.xml)
  catkin_run_tests_target(python package python-package.xml
    COMMAND "${PYTHON_EXECUTABLE} -m pytest -q -p no:cacheprovider -c /dev/null -o junit_family=xunit1 -o junit_suite_name=python_package --junitxml=${_python_package_result} ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/test_python_package.py"
    DEPENDENCIES top_sim_python ${PROJECT_NAME}_generate_messages_py)
  # Time: /clock followed under use_sim_time, monotonic through ~reset and ~spawn; replay of a recorded bag.
  add_rostest(test/ros/clock.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  add_rostest(test/ros/replay.test DEPENDENCIES top_sim_node ${PROJECT_NAME}_generate_messages_py)
  if(TARGET top_sim_lcm)
    add_rostest_gtest(top_sim_lcm_test test/ros/lcm.test test/ros/test_lcm.cpp)
    target_link_libraries(top_sim_lcm_test top_sim_lcm ${catkin_LIBRARIES})
    target_include_directories(top_sim_lcm_test PRIVATE ${catkin_INCLUDE_DIRS})
    add_dependencies(top_sim_lcm_test top_sim_node ${PROJECT_NAME}_generate_messages_cpp)
  endif()
endif()

include(${CMAKE_CURRENT_SOURCE_DIR}/cmake/ros_tools.cmake OPTIONAL)
