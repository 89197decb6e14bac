# bench/peer_mujoco: the frictionless top side by side with MuJoCo (issue 21 item 5, docs/performance.md).
# Built only where MuJoCo's library and headers are found (e.g. Debian's libmujoco-dev); nothing else depends on it.
option(TOP_SIM_PEER_MUJOCO "Build bench/peer_mujoco when MuJoCo is found" ON)
if(TOP_SIM_PEER_MUJOCO)
  find_path(MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
  find_library(MUJOCO_LIBRARY mujoco)
  if(MUJOCO_INCLUDE_DIR AND MUJOCO_LIBRARY)
    message(STATUS "MuJoCo: ${MUJOCO_LIBRARY}; building peer_mujoco")
    add_executable(peer_mujoco bench/peer_mujoco/peer_mujoco.cpp bench/peer_mujoco/mujoco_top.cpp
                               bench/peer_mujoco/pivot.cpp bench/peer_mujoco/mujoco_shapes.cpp
                               bench/peer_mujoco/euler_disk.cpp)
    target_include_directories(peer_mujoco PRIVATE ${MUJOCO_INCLUDE_DIR})
    target_link_libraries(peer_mujoco top_sim_core ${MUJOCO_LIBRARY})
    target_compile_definitions(peer_mujoco PRIVATE TOP_SIM_PEER_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config")
    if(TOP_SIM_TESTS)
      # Agreement only, no timing: the initial-state mapping, the reference, MuJoCo within 0.2 mm (about 0.5 s).
      add_test(NAME peer_mujoco_check COMMAND peer_mujoco --check)
      # Physics only (issue 34 item 4): the tutorial tippe top inverts onto its stem; Euler's disk holds its steady
      # rolling at a fine timestep.
      add_test(NAME peer_mujoco_tippe_top_check COMMAND peer_mujoco --tippe-top --check)
      add_test(NAME peer_mujoco_euler_disk_check COMMAND peer_mujoco --euler-disk --check)
    endif()
  else()
    message(STATUS "MuJoCo not found: peer_mujoco is not built")
  endif()
endif()
