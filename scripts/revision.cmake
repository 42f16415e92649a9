# Writes OUT, a header with the source revision (git describe, "-dirty" with local changes;
# "unknown" outside a git checkout), rewriting it only when the revision changed, so that
# a build recompiles one file per new commit. Run by CMakeLists.txt at every build.
execute_process(COMMAND git -C "${SOURCE}" describe --always --dirty --abbrev=7
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET RESULT_VARIABLE failed)
if(failed OR revision STREQUAL "")
  set(revision "unknown")
endif()
set(content "#define FDPARTICLE_REVISION \"${revision}\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT "${old}" STREQUAL "${content}")
  file(WRITE "${OUT}" "${content}")
endif()
