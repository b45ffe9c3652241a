# The camera simulator (tests/sim) as a static library: screens, the field
# mixed in, a phone camera photographing them. The tests and benchmarks link
# one (umf_sim), the sanitizer build its own (umf_sanitizer_sim); a build
# without OpenCV leaves out the tests that need it.
function(umf_add_sim_library name)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/*.cpp)
  list(FILTER sources EXCLUDE REGEX "_test\\.cpp$")
  add_library(${name} STATIC ${sources})
  target_include_directories(${name} SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
  target_link_libraries(${name} PUBLIC umf::umf ${OpenCV_LIBS})
endfunction()

# Drops from the list in `sources_var` the tests that need OpenCV or the
# simulator: those that decode images or photograph screens.
function(umf_drop_tests_needing_opencv sources_var)
  set(kept)
  foreach(source ${${sources_var}})
    file(READ ${source} text)
    if(NOT text MATCHES "#include [<\"](opencv2/|sim/|bench/|(detect/)?photo\\.hpp)")
      list(APPEND kept ${source})
    endif()
  endforeach()
  set(${sources_var} ${kept} PARENT_SCOPE)
endfunction()
