# GoogleTest for the core (one executable, every test/core/*.cpp) and Google Benchmark targets.
if(CATKIN_ENABLE_TESTING)
  file(GLOB TOP_SIM_CORE_TESTS ${CMAKE_CURRENT_SOURCE_DIR}/test/core/*.cpp)
  catkin_add_gtest(top_sim_core_tests ${TOP_SIM_CORE_TESTS})
  if(TARGET top_sim_core_tests)
    target_link_libraries(top_sim_core_tests top_sim_cli_common gtest_main)  # catkin links gtest only
    target_compile_definitions(top_sim_core_tests PRIVATE
      TOP_SIM_TEST_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config"
      TOP_SIM_TEST_RUN_BINARY="$<TARGET_FILE:top_sim_run>")
    add_dependencies(top_sim_core_tests top_sim_run)
  endif()
endif()

find_package(benchmark QUIET)
if(benchmark_FOUND)
  file(GLOB TOP_SIM_BENCH_SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/bench/*.cpp)
  foreach(src ${TOP_SIM_BENCH_SOURCES})
    get_filename_component(name ${src} NAME_WE)
    add_executable(${name} ${src})
    target_link_libraries(${name} top_sim_cli_common benchmark::benchmark)
    target_compile_definitions(${name} PRIVATE TOP_SIM_BENCH_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config")
  endforeach()
endif()
