# What the end-to-end scripts of tests/cli share: their arguments, a copy of the room, and
# running the `relight` binary with checks on its exit code and output.
# Included by each script, which is run as
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P script
cmake_minimum_required(VERSION 3.25)
foreach(var RELIGHT SCENE WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "define ${var}")
  endif()
endforeach()

# A fresh copy of the room's inputs in `dir` (no truth: the engine never reads it).
function(copy_room dir)
  file(REMOVE_RECURSE "${dir}")
  file(MAKE_DIRECTORY "${dir}")
  foreach(f scene.json room.obj photo.exr photo.mask.png)
    file(COPY_FILE "${SCENE}/${f}" "${dir}/${f}")
  endforeach()
endfunction()

# Runs the command after `expected_rc` and checks its exit code; its stdout and stderr go
# to `out`.
function(run_checked out expected_rc)
  execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE o ERROR_VARIABLE e RESULT_VARIABLE rc)
  if(NOT rc EQUAL expected_rc)
    message(FATAL_ERROR "${ARGN}: exit code ${rc}, expected ${expected_rc}\n${o}${e}")
  endif()
  set(${out} "${o}${e}" PARENT_SCOPE)
endfunction()

# Runs relight with the arguments after `expected_rc` (run_checked).
function(relight out expected_rc)
  run_checked(o ${expected_rc} "${RELIGHT}" ${ARGN})
  set(${out} "${o}" PARENT_SCOPE)
endfunction()

function(expect text regex what)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "${what}: expected /${regex}/ in:\n${text}")
  endif()
endfunction()

function(expect_not text regex what)
  if(text MATCHES "${regex}")
    message(FATAL_ERROR "${what}: did not expect /${regex}/ in:\n${text}")
  endif()
endfunction()
