# ctest script: installs the build into a scratch prefix, builds test/consumer against it with
# find_package(top_sim_core), and runs the consumer (which must find the installed data, not the sources').
# Installed under DESTDIR, not with --prefix: catkin's Python install (setup.py) keeps the configured prefix and
# honours only DESTDIR. The tree is then used where it lands, away from the configured prefix. Outside the sources
# (the catkin workspace lies in them): rosrun searches the package's directory and would find a second top_sim_node.
string(MD5 build_tag ${BUILD_DIR})
set(destdir /tmp/top_sim_install_check_${build_tag})
set(prefix ${destdir}${INSTALL_PREFIX})
set(consumer_build ${BUILD_DIR}/test_consumer)
file(REMOVE_RECURSE ${destdir} ${consumer_build})
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()
run_step(${CMAKE_COMMAND} -E env DESTDIR=${destdir} ${CMAKE_COMMAND} --install ${BUILD_DIR})
run_step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/test/consumer -B ${consumer_build} -DCMAKE_PREFIX_PATH=${prefix}
         -DCMAKE_BUILD_TYPE=Release)
run_step(${CMAKE_COMMAND} --build ${consumer_build})
# Without TOP_SIM_CONFIG_DIR and outside the source tree: the data must come from <prefix>/share/top_sim/config.
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=TOP_SIM_CONFIG_DIR ${consumer_build}/consumer
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer failed (${rc})")
endif()
get_filename_component(expected ${prefix}/share/top_sim/config REALPATH)
string(FIND "${out}" "config ${expected}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "consumer read its data from elsewhere than ${expected}")
endif()

# The installed tool in a clean environment (no LD_LIBRARY_PATH, no PATH): its RPATH finds libtop_sim_core.so.
run_step(env -i ${prefix}/${INSTALL_BIN}/top_sim_run ${prefix}/share/top_sim/config/scenes/default.yaml
         --duration 0.05 --quiet)
# The installed Python module from its documented place, equally clean.
if(PYTHON_MODULE)
  # (a script file: a `;` in a -c argument would split it as a CMake list)
  file(WRITE ${consumer_build}/import_top_sim.py
       "import top_sim\ntop_sim.Simulator('default').run(0.01)\nprint('top_sim module from', top_sim.__file__)\n")
  run_step(env -i PYTHONPATH=${prefix}/${INSTALL_PYTHON} /usr/bin/python3 ${consumer_build}/import_top_sim.py)
endif()

file(REMOVE_RECURSE ${destdir})  # kept only after a failure, to look at
