# One interface target carries the project's warning and sanitizer flags,
# so every library, tool and test links the same settings.
add_library(hba_warnings INTERFACE)
target_compile_options(hba_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow=local)
if(HBA_WERROR)
  target_compile_options(hba_warnings INTERFACE -Werror)
endif()

if(HBA_SANITIZE)
  target_compile_options(hba_warnings INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(hba_warnings INTERFACE -fsanitize=address,undefined)
endif()
if(HBA_SANITIZE_THREAD)
  if(HBA_SANITIZE)
    message(FATAL_ERROR "HBA_SANITIZE_THREAD and HBA_SANITIZE cannot be combined (one sanitizer runtime per build)")
  endif()
  target_compile_options(hba_warnings INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(hba_warnings INTERFACE -fsanitize=thread)
endif()
