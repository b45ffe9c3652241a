# Unity builds for the targets with many sources that each parse the same
# heavy headers (Qt, Boost.Beast, OpenCV, GoogleTest) and instantiate the
# same templates: compiled eight at a time, the release and sanitizer builds
# take about half the time (docs/CI.md). A source is compiled alone when it
# includes the X11 or Wayland client headers (their macros, None, Status and
# Bool among them, break the Qt headers of any source after it in a batch)
# or is not C++ (the generated Wayland protocol code). Names private to a
# source file (its anonymous namespace) must differ from those of the other
# sources of the target: a clash is a compile error, fixed by a clearer name.
set(UMF_UNITY_BATCH_SIZE 8 CACHE STRING "Sources compiled together in a unity build (0: no unity build)")

function(umf_unity_build target)
  if(UMF_UNITY_BATCH_SIZE LESS 2)
    return()
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${UMF_UNITY_BATCH_SIZE})
  get_target_property(sources ${target} SOURCES)
  get_target_property(source_dir ${target} SOURCE_DIR)
  foreach(source ${sources})
    if(NOT IS_ABSOLUTE ${source})
      set(source ${source_dir}/${source})
    endif()
    set(alone FALSE)
    if(NOT source MATCHES "\\.cpp$")
      set(alone TRUE)
    elseif(EXISTS ${source})
      file(STRINGS ${source} desktop_includes REGEX "^#include [<\"][^>\"]*([Xx]11|wayland|wlroots|xcb|kwin_fake_pointer)")
      if(desktop_includes)
        set(alone TRUE)
      endif()
    endif()
    if(alone)
      set_source_files_properties(${source} TARGET_DIRECTORY ${target} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
    endif()
  endforeach()
endfunction()
