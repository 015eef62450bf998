# Run at build time (cmake -P): writes OUTPUT with the source tree's revision, "-dirty" when it
# has uncommitted changes, so reports name the code they came from. The file is rewritten only
# when the revision changes, so unchanged builds recompile nothing.
execute_process(COMMAND git describe --always --dirty --abbrev=7 WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT revision)
  set(revision unknown)
endif()
set(content "// Generated at build time by cmake/GitRevision.cmake.\n#define HMB_GIT_REVISION \"${revision}\"\n")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} previous)
endif()
if(NOT "${previous}" STREQUAL "${content}")
  file(WRITE ${OUTPUT} "${content}")
endif()
