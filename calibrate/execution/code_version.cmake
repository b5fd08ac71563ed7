# Writes OUTPUT, a header defining GRADEM_CODE_VERSION: "VERSION+<commit>" from the git
# checkout at SOURCE_DIR, with "-dirty.<hash>" when its tracked files differ from that commit
# (<hash>: the first 8 hex digits of the SHA-1 of `git diff HEAD`, so two different edits of
# one commit get two versions; untracked files are not in it), "VERSION+unknown" outside a
# checkout. Run at every build (calibrate/CMakeLists.txt); the file is rewritten only when the
# version changes, so an unchanged tree recompiles nothing.
#   cmake -DSOURCE_DIR=... -DOUTPUT=... -DVERSION=... -P code_version.cmake
set(version "${VERSION}+unknown")
find_program(GIT git)
if(GIT)
  execute_process(COMMAND ${GIT} rev-parse --short=12 HEAD WORKING_DIRECTORY ${SOURCE_DIR}
                  OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  if(rc EQUAL 0 AND commit)
    set(version "${VERSION}+${commit}")
    execute_process(COMMAND ${GIT} diff HEAD --no-color --no-ext-diff WORKING_DIRECTORY ${SOURCE_DIR}
                    OUTPUT_VARIABLE diff ERROR_QUIET RESULT_VARIABLE rc)
    if(rc EQUAL 0 AND NOT diff STREQUAL "")
      string(SHA1 diff_hash "${diff}")
      string(SUBSTRING "${diff_hash}" 0 8 diff_hash)
      set(version "${version}-dirty.${diff_hash}")
    endif()
  endif()
endif()
set(text "#pragma once\n// Generated at build time by calibrate/execution/code_version.cmake.\n#define GRADEM_CODE_VERSION \"${version}\"\n")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
