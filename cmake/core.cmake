# The physics core library and the ROS-free command-line tools.
file(GLOB TOP_SIM_CORE_SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/src/core/*.cpp)
add_library(top_sim_core ${TOP_SIM_CORE_SOURCES})
target_include_directories(top_sim_core PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> ${EIGEN3_INCLUDE_DIR} ${Boost_INCLUDE_DIRS})
target_link_libraries(top_sim_core PUBLIC yaml-cpp)
target_compile_definitions(top_sim_core PRIVATE
  TOP_SIM_SOURCE_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config")
set_target_properties(top_sim_core PROPERTIES POSITION_INDEPENDENT_CODE ON)

add_library(top_sim_cli_common src/cli/run_output.cpp)
target_link_libraries(top_sim_cli_common PUBLIC top_sim_core)

add_executable(top_sim_run src/cli/top_sim_run.cpp)
target_link_libraries(top_sim_run top_sim_cli_common)
# Optional LCM bridge: `top_sim_run --lcm URL` streams in real time without ROS.
include(${CMAKE_CURRENT_LIST_DIR}/lcm.cmake)
if(TARGET top_sim_lcm)
  target_link_libraries(top_sim_run top_sim_lcm)
endif()

