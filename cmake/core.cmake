# The physics core library (no ROS, no LCM), the shared CLI code and top_sim_run.
file(GLOB TOP_SIM_CORE_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/core/*.cpp)
add_library(top_sim_core SHARED ${TOP_SIM_CORE_SOURCES})
add_library(top_sim::top_sim_core ALIAS top_sim_core)
target_include_directories(top_sim_core PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${TOP_SIM_INSTALL_INCLUDE}>)
target_link_libraries(top_sim_core PUBLIC Eigen3::Eigen Boost::headers yaml-cpp PRIVATE ${CMAKE_DL_LIBS})
# Relative path from the directories holding binaries to the data (data_path.cpp searches upwards for it).
target_compile_definitions(top_sim_core PRIVATE TOP_SIM_DATA_SUBDIR="share/${PROJECT_NAME}/config")
set_target_properties(top_sim_core PROPERTIES POSITION_INDEPENDENT_CODE ON)

# What every tool writes (CSV, summary, plots) and reads (arguments): top_sim_run, top_sim_bag, the CLI tools.
# ROS-free, above the core; the tools are thin adapters over both (docs/architecture.md).
add_library(top_sim_output src/output/run.cpp src/output/writers.cpp src/output/plot.cpp src/output/command_line.cpp)
target_include_directories(top_sim_output PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/src/output)
# JSON through nlohmann-json and command lines through CLI11, both private: no tool's header includes them.
target_link_libraries(top_sim_output PUBLIC top_sim_core PRIVATE nlohmann_json::nlohmann_json CLI11::CLI11)

# The studies: a sweep's point and flags, a fit's data. Library code the command-line tools and Python both link,
# so src/cli holds adapters only.
add_library(top_sim_studies src/studies/sweep_point.cpp src/studies/sweep_options.cpp src/studies/fit_data.cpp)
target_include_directories(top_sim_studies PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/src/studies)
target_link_libraries(top_sim_studies PUBLIC top_sim_output PRIVATE nlohmann_json::nlohmann_json)
# Position-independent: the Python module (a shared object) links the sweep's code (cmake/python.cmake).
set_target_properties(top_sim_output top_sim_studies PROPERTIES POSITION_INDEPENDENT_CODE ON)

add_executable(top_sim_run src/cli/top_sim_run.cpp)
target_link_libraries(top_sim_run top_sim_studies)
# Optional LCM bridge: `top_sim_run --lcm URL` streams in real time without ROS.
include(${CMAKE_CURRENT_LIST_DIR}/lcm.cmake)
if(TARGET top_sim_lcm)
  target_link_libraries(top_sim_run top_sim_lcm)
endif()
