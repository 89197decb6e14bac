# Fuzzing (docs/reliability.md, "Fuzzing"): the three targets of test/fuzz/fuzz_targets.hpp.
#   every plain build (sanitized or not, any compiler): top_sim_core_tests replays test/fuzz/corpus/<target>/*;
#   -DTOP_SIM_FUZZ=ON (clang): the libFuzzer executables fuzz_scene_loader, fuzz_command, fuzz_step (scripts/fuzz.sh).
option(TOP_SIM_FUZZ "Build the libFuzzer targets fuzz_scene_loader, fuzz_command, fuzz_step (needs clang)" OFF)
set(TOP_SIM_FUZZ_DIR ${CMAKE_CURRENT_SOURCE_DIR}/test/fuzz)
set(TOP_SIM_FUZZ_CONFIG_DIR ${CMAKE_CURRENT_SOURCE_DIR}/config)

if(TARGET top_sim_core_tests)
  target_sources(top_sim_core_tests PRIVATE ${TOP_SIM_FUZZ_DIR}/fuzz_targets.cpp ${TOP_SIM_FUZZ_DIR}/fuzz_seeds_test.cpp)
  target_compile_definitions(top_sim_core_tests PRIVATE
    TOP_SIM_FUZZ_CONFIG_DIR="${TOP_SIM_FUZZ_CONFIG_DIR}" TOP_SIM_FUZZ_CORPUS_DIR="${TOP_SIM_FUZZ_DIR}/corpus")
endif()

if(NOT TOP_SIM_FUZZ)
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "TOP_SIM_FUZZ needs clang's libFuzzer: configure with CXX=clang++ (scripts/fuzz.sh does)")
endif()

# The core gets coverage instrumentation (no libFuzzer main); everything that links it gets ASan + UBSan.
set(TOP_SIM_FUZZ_CHECKS -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
target_compile_options(top_sim_core PRIVATE -fsanitize=fuzzer-no-link ${TOP_SIM_FUZZ_CHECKS})
target_link_options(top_sim_core PUBLIC -fsanitize=address,undefined)
foreach(name scene_loader command step)
  add_executable(fuzz_${name} ${TOP_SIM_FUZZ_DIR}/fuzz_${name}.cpp ${TOP_SIM_FUZZ_DIR}/fuzz_targets.cpp)
  target_link_libraries(fuzz_${name} top_sim_core)
  target_compile_options(fuzz_${name} PRIVATE -fsanitize=fuzzer ${TOP_SIM_FUZZ_CHECKS})
  target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  target_compile_definitions(fuzz_${name} PRIVATE TOP_SIM_FUZZ_CONFIG_DIR="${TOP_SIM_FUZZ_CONFIG_DIR}")
endforeach()
