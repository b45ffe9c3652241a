# The camera simulator (tests/sim) as a static library: screens, the field
# mixed in, a phone camera photographing them. The tests and benchmarks link
# one (umf_sim), the sanitizer build its own (umf_sanitizer_sim).
function(umf_add_sim_library name)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/*.cpp)
  list(FILTER sources EXCLUDE REGEX "_test\\.cpp$")
  add_library(${name} STATIC ${sources})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/..)
  target_include_directories(${name} SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
  target_link_libraries(${name} PUBLIC umf::umf ${OpenCV_LIBS})
endfunction()
