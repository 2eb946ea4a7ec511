# hba_write_if_changed(<file> <text>): writes the file only when its text
# differs, so that what includes a generated file is rebuilt only then.
function(hba_write_if_changed file text)
  set(old "")
  if(EXISTS "${file}")
    file(READ "${file}" old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE "${file}" "${text}")
  endif()
endfunction()
