# Writes OUT, a header defining TUMBLE_COMMIT: the commit the build's sources are at (12 hex
# digits, "-dirty" with changes not committed), or "unknown" outside a git checkout. Run at
# every build (app/CMakeLists.txt); the file is rewritten only when the text changes, so
# only the one source that includes it is compiled again. (--exclude=*: the commit's hash even
# where a tag names it.)
execute_process(COMMAND git -C "${SOURCE}" describe --always --dirty --abbrev=12 --exclude=*
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE status ERROR_QUIET)
if(NOT status EQUAL 0 OR commit STREQUAL "")
  set(commit "unknown")
endif()
set(text "#define TUMBLE_COMMIT \"${commit}\"\n")
set(old "")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
