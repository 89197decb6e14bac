# ctest script: installs the build into a scratch prefix, builds test/consumer against it with
# find_package(top_sim_core), and runs the consumer (which must find the installed data, not the sources').
set(prefix ${BUILD_DIR}/test_install)
set(consumer_build ${BUILD_DIR}/test_consumer)
file(REMOVE_RECURSE ${prefix} ${consumer_build})
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()
run_step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
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
