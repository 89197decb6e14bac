# The Python module `top_sim` (pybind11), built into <build>/python; plain build only: in a catkin build the
# name top_sim belongs to the generated message package (top_sim.msg).
if(NOT TOP_SIM_PYTHON OR TOP_SIM_ROS)
  return()
endif()
find_package(Python3 COMPONENTS Interpreter Development REQUIRED)
set(PYBIND11_PYTHON_VERSION ${Python3_VERSION})
set(PYBIND11_FINDPYTHON ON)
find_package(pybind11 CONFIG REQUIRED)
pybind11_add_module(top_sim_python src/python/top_sim_module.cpp)
target_link_libraries(top_sim_python PRIVATE top_sim_core)
file(RELATIVE_PATH _python_to_lib /${TOP_SIM_INSTALL_PYTHON} /${TOP_SIM_INSTALL_LIB})
set_target_properties(top_sim_python PROPERTIES OUTPUT_NAME top_sim
  LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/python INSTALL_RPATH "$ORIGIN/${_python_to_lib}")
install(TARGETS top_sim_python LIBRARY DESTINATION ${TOP_SIM_INSTALL_PYTHON})

if(TOP_SIM_TESTS)
  add_test(NAME python_tests
    COMMAND ${Python3_EXECUTABLE} -m pytest -q -p no:cacheprovider ${CMAKE_CURRENT_SOURCE_DIR}/test/python
            --junitxml=${TOP_SIM_TEST_RESULTS}/python_tests.xml)
  set_tests_properties(python_tests PROPERTIES
    ENVIRONMENT "PYTHONPATH=${PROJECT_BINARY_DIR}/python;TOP_SIM_RUN_BINARY=$<TARGET_FILE:top_sim_run>")
endif()
