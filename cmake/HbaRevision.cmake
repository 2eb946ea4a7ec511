# Script mode (cmake -P), run at every build: writes OUTPUT (a header with
# HBA_REVISION, the git revision of SOURCE_DIR, "-dirty" with local changes,
# or "unknown" outside a git checkout) only when it changed, so a commit
# rebuilds what prints the version and nothing else does.
execute_process(COMMAND git -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE failed ERROR_QUIET)
if(failed OR revision STREQUAL "")
  set(revision "unknown")
endif()
set(text "#pragma once\n#define HBA_REVISION \"${revision}\"\n")
include(${CMAKE_CURRENT_LIST_DIR}/HbaWriteIfChanged.cmake)
hba_write_if_changed("${OUTPUT}" "${text}")
