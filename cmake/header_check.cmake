# The installed surface, checked: every header in include/top_sim is listed in TOP_SIM_INSTALLED_HEADERS, and each
# compiles on its own (one generated source per header including only it, compiled, not linked, by default builds).
file(GLOB top_sim_unlisted_headers CONFIGURE_DEPENDS RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/include/top_sim
  ${CMAKE_CURRENT_SOURCE_DIR}/include/top_sim/*.hpp)
list(REMOVE_ITEM top_sim_unlisted_headers ${TOP_SIM_INSTALLED_HEADERS})
if(top_sim_unlisted_headers)
  message(FATAL_ERROR "include/top_sim holds headers not in TOP_SIM_INSTALLED_HEADERS (cmake/core_install.cmake): "
    "${top_sim_unlisted_headers}; list them there, or move an internal one to src/core")
endif()

if(TOP_SIM_TESTS)
  set(top_sim_header_check_sources)
  foreach(header ${TOP_SIM_INSTALLED_HEADERS})
    string(REPLACE ".hpp" "" stem ${header})
    set(source ${PROJECT_BINARY_DIR}/header_check/${stem}.cpp)
    # file(GENERATE): rewritten only when the text changes, so a rebuild compiles nothing new.
    file(GENERATE OUTPUT ${source} CONTENT "#include \"top_sim/${header}\"\n")
    list(APPEND top_sim_header_check_sources ${source})
  endforeach()
  add_library(top_sim_header_check OBJECT ${top_sim_header_check_sources})
  # The core's usage requirements only (include directories, Eigen, Boost, yaml-cpp): what an installed user gets.
  target_link_libraries(top_sim_header_check PRIVATE top_sim_core)
  top_sim_test_only(top_sim_header_check)
endif()
