# Sanitizer build: -DHMB_SANITIZE=address,undefined (or ON, the same) instruments everything
# the project compiles and links (libraries, hmblur, hmblur-bench, the example, the tests) with
# AddressSanitizer (LeakSanitizer included) and UndefinedBehaviorSanitizer; any UB aborts the
# process, so a finding fails its test. Use a build folder of its own (README "Sanitizers").
# The GLSL kernels are unaffected: glslangValidator compiles them, lavapipe JITs them.
set(HMB_SANITIZE "" CACHE STRING
    "Sanitizers for every target: empty (none), ON (= address,undefined), or a -fsanitize= list")

# Every executable of the project, in every folder: linked with `lib` (an object library).
function(hmb_sanitizer_link_executables dir lib)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      set_property(TARGET ${target} APPEND PROPERTY LINK_LIBRARIES ${lib})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(subdir IN LISTS subdirs)
    hmb_sanitizer_link_executables(${subdir} ${lib})
  endforeach()
endfunction()

if(HMB_SANITIZE)
  if(HMB_SANITIZE STREQUAL "ON" OR HMB_SANITIZE STREQUAL "1" OR HMB_SANITIZE STREQUAL "TRUE")
    set(HMB_SANITIZE "address,undefined")
  endif()
  message(STATUS "Sanitizers: -fsanitize=${HMB_SANITIZE} (build type ${CMAKE_BUILD_TYPE})")
  set(hmb_sanitize_flags -fsanitize=${HMB_SANITIZE} -fno-omit-frame-pointer)
  if(HMB_SANITIZE MATCHES "undefined")
    list(APPEND hmb_sanitize_flags -fno-sanitize-recover=undefined)
  endif()
  # Directory scope, before any add_subdirectory: every target below gets them.
  add_compile_options(${hmb_sanitize_flags})
  add_link_options(${hmb_sanitize_flags})

  # Vulkan libraries stay loaded until exit, so LeakSanitizer can see and name what they hold
  # (tests/sanitizers/keep_libraries_loaded.cpp); added to every executable once all are made.
  # (ASAN_OPTIONS=fast_unwind_on_malloc=0 is no alternative: lavapipe's LLVM registers JIT
  # frames with libgcc, whose unwinder then allocates under its own lock and deadlocks.)
  add_library(hmb_keep_libraries_loaded OBJECT
              ${PROJECT_SOURCE_DIR}/tests/sanitizers/keep_libraries_loaded.cpp)
  cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL
                 hmb_sanitizer_link_executables ${PROJECT_SOURCE_DIR} hmb_keep_libraries_loaded)
endif()

# The sanitizer options of every test of a gtest_discover_tests target (tests/CMakeLists.txt),
# on top of its ENVIRONMENT; child processes (hmblur, hmblur-bench, render_frame) inherit them.
# Set from a CTest include file read after the discovered tests, because gtest_discover_tests
# flattens list-valued PROPERTIES (only the first of several ENVIRONMENT entries survives).
#   UBSAN_OPTIONS print_stacktrace=1: UBSan prints only the source line otherwise.
#   LSAN_OPTIONS suppressions: leaks inside the Vulkan libraries (tests/sanitizers/lsan.supp).
function(hmb_sanitizer_test_environment target)
  if(NOT HMB_SANITIZE)
    return()
  endif()
  set(env "UBSAN_OPTIONS=set:print_stacktrace=1"
          "LSAN_OPTIONS=set:suppressions=${PROJECT_SOURCE_DIR}/tests/sanitizers/lsan.supp")
  set(script ${CMAKE_CURRENT_BINARY_DIR}/${target}_sanitizers.cmake)
  file(CONFIGURE OUTPUT ${script} @ONLY CONTENT [=[
if(@target@_TESTS)
  set_tests_properties(${@target@_TESTS} PROPERTIES ENVIRONMENT_MODIFICATION "@env@")
endif()
]=])
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${script})
endfunction()
