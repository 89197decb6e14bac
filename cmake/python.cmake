# The Python package `top_sim`: the sources of src/python/top_sim (top_sim.sweep, __init__.py) and the compiled
# physics module top_sim._core (pybind11) side by side. Plain build: all in <build>/python/top_sim. Catkin build:
# catkin_python_setup (setup.py, in ros.cmake) serves src/python/top_sim from the devel space, next to the
# generated top_sim.msg and top_sim.srv, and _core lands in the devel space's top_sim directory.
if(NOT TOP_SIM_PYTHON)
  return()
endif()
find_package(Python3 COMPONENTS Interpreter Development REQUIRED)
set(PYBIND11_PYTHON_VERSION ${Python3_VERSION})
set(PYBIND11_FINDPYTHON ON)
find_package(pybind11 CONFIG REQUIRED)
pybind11_add_module(top_sim_python src/python/top_sim_module.cpp src/python/sweep_module.cpp)
target_link_libraries(top_sim_python PRIVATE top_sim_core top_sim_studies)
if(TOP_SIM_ROS)
  # catkin's devel and install destinations of the package's Python modules (catkin_package() is not called yet).
  set(_python_dir ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_PYTHON_DESTINATION}/top_sim)
  set(TOP_SIM_INSTALL_PYTHON ${CATKIN_GLOBAL_PYTHON_DESTINATION})
else()
  set(_python_dir ${PROJECT_BINARY_DIR}/python/top_sim)
  # The package's Python sources, linked into the build tree (edits apply without a build).
  file(GLOB _python_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/python/top_sim/*.py)
  file(MAKE_DIRECTORY ${_python_dir})
  foreach(_source ${_python_sources})
    get_filename_component(_name ${_source} NAME)
    if(NOT EXISTS ${_python_dir}/${_name})
      file(CREATE_LINK ${_source} ${_python_dir}/${_name} SYMBOLIC)
    endif()
  endforeach()
  install(FILES ${_python_sources} DESTINATION ${TOP_SIM_INSTALL_PYTHON}/top_sim)
endif()
file(RELATIVE_PATH _python_to_lib /${TOP_SIM_INSTALL_PYTHON}/top_sim /${TOP_SIM_INSTALL_LIB})
set_target_properties(top_sim_python PROPERTIES OUTPUT_NAME _core
  LIBRARY_OUTPUT_DIRECTORY ${_python_dir} INSTALL_RPATH "$ORIGIN/${_python_to_lib}")
install(TARGETS top_sim_python LIBRARY DESTINATION ${TOP_SIM_INSTALL_PYTHON}/top_sim)

if(TOP_SIM_TESTS)
  # The package's root on sys.path: the plain build's python/, or catkin's devel space (sources, msg and _core).
  get_filename_component(_python_root ${_python_dir} DIRECTORY)
  add_test(NAME python_tests
    COMMAND ${Python3_EXECUTABLE} -m pytest -q -p no:cacheprovider ${CMAKE_CURRENT_SOURCE_DIR}/test/python
            --junitxml=${TOP_SIM_TEST_RESULTS}/python_tests.xml)
  set_tests_properties(python_tests PROPERTIES
    ENVIRONMENT "PYTHONPATH=${_python_root};TOP_SIM_RUN_BINARY=$<TARGET_FILE:top_sim_run>;TOP_SIM_SWEEP_BINARY=$<TARGET_FILE:top_sim_sweep>")
endif()
