# Tests of the core (GoogleTest, pytest, the install/export check, through ctest) and Google Benchmark targets.
# In both builds: the plain one builds them by default; the catkin one with its `tests` target (catkin_make tests),
# so scripts/test.sh builds the core once in Release, and quickstart.sh does not wait for the test binaries.
if(TOP_SIM_TESTS)
  find_package(GTest REQUIRED)
  file(GLOB TOP_SIM_CORE_TESTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/core/*.cpp)
  add_executable(top_sim_core_tests ${TOP_SIM_CORE_TESTS})
  top_sim_test_only(top_sim_core_tests)
  target_link_libraries(top_sim_core_tests top_sim_studies GTest::gtest GTest::gtest_main)
  target_compile_definitions(top_sim_core_tests PRIVATE
    TOP_SIM_TEST_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config"
    TOP_SIM_TEST_RUN_BINARY="$<TARGET_FILE:top_sim_run>"
    TOP_SIM_TEST_FIT_BINARY="$<TARGET_FILE:top_sim_fit>"
    TOP_SIM_TEST_STABILITY_BINARY="$<TARGET_FILE:top_sim_stability>")
  add_dependencies(top_sim_core_tests top_sim_run top_sim_sweep top_sim_fit top_sim_stability)  # the CLI tests run them
  # In shards (GoogleTest's GTEST_TOTAL_SHARDS), so `ctest -j2` keeps both cores busy; each shard its own TempDir.
  set(TOP_SIM_CORE_TEST_SHARDS 2 CACHE STRING "Processes the core's GoogleTest suite is split into under ctest")
  math(EXPR last_shard "${TOP_SIM_CORE_TEST_SHARDS} - 1")
  foreach(shard RANGE ${last_shard})
    set(shard_tmp ${PROJECT_BINARY_DIR}/core_tests_tmp/${shard})
    file(MAKE_DIRECTORY ${shard_tmp})
    add_test(NAME core_tests_${shard}
      COMMAND top_sim_core_tests --gtest_output=xml:${TOP_SIM_TEST_RESULTS}/core_tests_${shard}.xml)
    set_tests_properties(core_tests_${shard} PROPERTIES ENVIRONMENT
      "GTEST_TOTAL_SHARDS=${TOP_SIM_CORE_TEST_SHARDS};GTEST_SHARD_INDEX=${shard};TEST_TMPDIR=${shard_tmp}/")
  endforeach()

  # The LCM stream as top_sim_lcm_echo prints it: every field of lcm/top_state_t.lcm (multicast route needed).
  if(TARGET top_sim_lcm_echo)
    add_test(NAME lcm_echo COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/lcm_echo_test.sh
      $<TARGET_FILE:top_sim_run> $<TARGET_FILE:top_sim_lcm_echo> ${CMAKE_CURRENT_SOURCE_DIR})
  endif()

  # No function over 60 lines without a reason in its comment (scripts/check_function_length.py).
  find_package(Python3 COMPONENTS Interpreter REQUIRED)
  add_test(NAME function_length COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_function_length.py)

  # Another CMake project links the installed core through find_package(top_sim_core).
  # The installed tools and Python module run in a clean environment (env -i): RPATH and install layout.
  add_test(NAME install_and_find_package COMMAND ${CMAKE_COMMAND}
    -DBUILD_DIR=${PROJECT_BINARY_DIR} -DSOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR} -DINSTALL_PREFIX=${CMAKE_INSTALL_PREFIX}
    -DPYTHON_MODULE=$<TARGET_EXISTS:top_sim_python> -DINSTALL_BIN=${TOP_SIM_INSTALL_BIN}
    -DINSTALL_PYTHON=${TOP_SIM_INSTALL_PYTHON}
    -P ${CMAKE_CURRENT_SOURCE_DIR}/test/consumer/check_install.cmake)
endif()

# model.kind auto against the full model (docs/analysis.md): a plain program, built with or without benchmark.
if(NOT TOP_SIM_ROS)
  add_executable(auto_bench ${CMAKE_CURRENT_SOURCE_DIR}/bench/auto_bench.cpp)
  target_link_libraries(auto_bench top_sim_studies)
endif()

find_package(benchmark QUIET)
if(benchmark_FOUND)
  file(GLOB TOP_SIM_BENCH_SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/bench/*.cpp)
  list(FILTER TOP_SIM_BENCH_SOURCES EXCLUDE REGEX "auto_bench[.]cpp$")
  foreach(src ${TOP_SIM_BENCH_SOURCES})
    get_filename_component(name ${src} NAME_WE)
    add_executable(${name} ${src})
    target_link_libraries(${name} top_sim_studies benchmark::benchmark)
  endforeach()
endif()
