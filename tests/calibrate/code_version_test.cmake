# calibrate/execution/code_version.cmake on throw-away git checkouts: the commit of a clean
# tree, a dirty mark that follows the diff (two edits, two marks; undone, none), "unknown"
# outside a checkout, and a header left untouched when the version has not changed.
#   cmake -DSCRIPT=.../code_version.cmake -DWORK=<empty dir> -P code_version_test.cmake
function(check_version dir expected_regex what)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${dir} -DOUTPUT=${WORK}/v.hpp -DVERSION=9.8.7 -P ${SCRIPT}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}: the script failed (${rc})")
  endif()
  file(READ ${WORK}/v.hpp text)
  if(NOT text MATCHES "#define GRADEM_CODE_VERSION \"(${expected_regex})\"")
    message(FATAL_ERROR "${what}: expected a version matching '${expected_regex}', got:\n${text}")
  endif()
  set(version ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()
function(git)
  execute_process(COMMAND git -c user.name=t -c user.email=t@t ${ARGN} WORKING_DIRECTORY ${WORK}/repo
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "git ${ARGN} failed")
  endif()
endfunction()

# WORK is inside the project's own checkout: git must not look above it.
set(ENV{GIT_CEILING_DIRECTORIES} ${WORK})
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/repo ${WORK}/plain)
check_version(${WORK}/plain "9\\.8\\.7\\+unknown" "outside a checkout")

file(WRITE ${WORK}/repo/law.hpp "double k = 1.0;\n")
git(init -q)
git(add law.hpp)
git(commit -q -m one)
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${WORK}/repo OUTPUT_VARIABLE commit
                OUTPUT_STRIP_TRAILING_WHITESPACE)
check_version(${WORK}/repo "9\\.8\\.7\\+${commit}" "a clean tree")

file(WRITE ${WORK}/repo/law.hpp "double k = 2.0;\n")
check_version(${WORK}/repo "9\\.8\\.7\\+${commit}-dirty\\.[0-9a-f]+" "an edited tree")
set(first ${version})
file(WRITE ${WORK}/repo/law.hpp "double k = 3.0;\n")
check_version(${WORK}/repo "9\\.8\\.7\\+${commit}-dirty\\.[0-9a-f]+" "another edit")
if(version STREQUAL first)
  message(FATAL_ERROR "two different edits got the same version ${version}")
endif()

file(WRITE ${WORK}/repo/law.hpp "double k = 1.0;\n")
check_version(${WORK}/repo "9\\.8\\.7\\+${commit}" "the edit undone")
# Unchanged version: the header is not rewritten (an unchanged tree recompiles nothing).
file(TIMESTAMP ${WORK}/v.hpp before "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
check_version(${WORK}/repo "9\\.8\\.7\\+${commit}" "again")
file(TIMESTAMP ${WORK}/v.hpp after "%s")
if(NOT before STREQUAL after)
  message(FATAL_ERROR "the header was rewritten with the same version")
endif()
