# Output and install directories. The build tree mirrors the install tree (bin/ or lib/top_sim/ next to
# share/top_sim/config), so the core finds its data relative to its own binary in both (data_path.cpp).
if(TOP_SIM_ROS)
  find_package(catkin REQUIRED)
  # catkin_package() (called in ros.cmake, after message generation) would set these; the core targets are
  # declared before it, so set them here: executables in devel/lib/top_sim (rosrun finds them).
  set(TOP_SIM_OUTPUT_PREFIX ${CATKIN_DEVEL_PREFIX})
  set(TOP_SIM_INSTALL_BIN lib/${PROJECT_NAME})
  set(TOP_SIM_INSTALL_LIB lib)
  set(TOP_SIM_INSTALL_INCLUDE include)
  set(TOP_SIM_INSTALL_SHARE share/${PROJECT_NAME})
else()
  include(GNUInstallDirs)
  set(TOP_SIM_OUTPUT_PREFIX ${PROJECT_BINARY_DIR})
  set(TOP_SIM_INSTALL_BIN ${CMAKE_INSTALL_BINDIR})
  set(TOP_SIM_INSTALL_LIB ${CMAKE_INSTALL_LIBDIR})
  set(TOP_SIM_INSTALL_INCLUDE ${CMAKE_INSTALL_INCLUDEDIR})
  set(TOP_SIM_INSTALL_SHARE ${CMAKE_INSTALL_DATADIR}/${PROJECT_NAME})
  # The Python module's install directory: PYTHONPATH=<prefix>/lib/python3/dist-packages (Debian's layout).
  set(TOP_SIM_INSTALL_PYTHON ${TOP_SIM_INSTALL_LIB}/python3/dist-packages)
endif()
enable_testing()
# JUnit XML of the core's test suites (ctest; scripts/test.sh counts the cases). Not catkin's test_results, which
# run_tests empties before the ROS tests run.
set(TOP_SIM_TEST_RESULTS ${PROJECT_BINARY_DIR}/test_results CACHE PATH "JUnit XML output of the core's tests")
# Installed binaries and libraries find the installed libraries relative to themselves (a clean environment, any
# prefix): from the binaries' directory, and (catkin's layout, lib/top_sim against lib) from the libraries' own.
file(RELATIVE_PATH TOP_SIM_BIN_TO_LIB /${TOP_SIM_INSTALL_BIN} /${TOP_SIM_INSTALL_LIB})
set(CMAKE_INSTALL_RPATH "$ORIGIN/${TOP_SIM_BIN_TO_LIB};$ORIGIN")
set(CMAKE_ARCHIVE_OUTPUT_DIRECTORY ${TOP_SIM_OUTPUT_PREFIX}/lib)
set(CMAKE_LIBRARY_OUTPUT_DIRECTORY ${TOP_SIM_OUTPUT_PREFIX}/lib)
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY ${TOP_SIM_OUTPUT_PREFIX}/${TOP_SIM_INSTALL_BIN})

# The data directory of the build tree: a link to the sources' config/ where the installed one will be.
set(TOP_SIM_BUILD_SHARE ${TOP_SIM_OUTPUT_PREFIX}/share/${PROJECT_NAME})
file(MAKE_DIRECTORY ${TOP_SIM_BUILD_SHARE})
if(NOT EXISTS ${TOP_SIM_BUILD_SHARE}/config)
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/config ${TOP_SIM_BUILD_SHARE}/config SYMBOLIC)
endif()

# A target only the tests need: built by default in the plain build, by catkin's `tests` target in the catkin one.
function(top_sim_test_only target)
  if(TOP_SIM_ROS)
    set_target_properties(${target} PROPERTIES EXCLUDE_FROM_ALL TRUE)
    add_dependencies(tests ${target})
  endif()
endfunction()
