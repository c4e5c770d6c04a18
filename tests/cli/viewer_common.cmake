# What the viewer's end-to-end scripts share (after common.cmake): the viewer run under a
# virtual X server, and the one-8-bit-step comparison of two images.
# Needs -DVIEWER=... -DXVFB_RUN=... (and -DVIEWER_PRELOAD=... under the sanitizers:
# tests/CMakeLists.txt says why). Starts from an empty ${WORK}.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)
foreach(var VIEWER XVFB_RUN)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "define ${var}")
  endif()
endforeach()
set(viewer_cmd "${VIEWER}")
if(VIEWER_PRELOAD)
  set(viewer_cmd env "LD_PRELOAD=${VIEWER_PRELOAD}" "${VIEWER}")
endif()
find_program(IDIFF idiff REQUIRED)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# Runs the viewer under xvfb-run (run_checked). With an X authority file of its own (-f),
# xvfb-run makes no temporary folder: its removal at exit raced the X server's reset on a
# loaded machine ("problem while cleaning up temporary directory", exit code 5, in place of
# the viewer's own).
function(viewer out expected_rc)
  run_checked(o ${expected_rc} "${XVFB_RUN}" -a -f "${WORK}/Xauthority" -s "-screen 0 1280x1024x24"
              ${viewer_cmd} ${ARGN})
  set(${out} "${o}" PARENT_SCOPE)
endfunction()

# idiff fails on any pixel further apart than `limit` (0: any difference at all).
function(same_within a b limit what)
  execute_process(COMMAND "${IDIFF}" -fail ${limit} -failpercent 0 "${a}" "${b}"
                  OUTPUT_VARIABLE o ERROR_VARIABLE e RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}: ${a} and ${b} differ by more than ${limit}\n${o}${e}")
  endif()
endfunction()

# One 8-bit step is 1/255 = 0.00392: idiff fails on any pixel further apart than 0.004. The
# screenshot is the display's 8-bit output, so that is as close as two displays can agree.
function(same_within_one_step a b what)
  same_within("${a}" "${b}" 0.004 "${what}: more than one 8-bit step")
endfunction()

# rel_rmse of `image` against truth/`edit` must be at most `bound`.
function(scores_within image edit bound what)
  relight(o 0 eval "${SCENE}" ${edit} "${image}")
  if(NOT o MATCHES "rel_rmse ([0-9.]+)")
    message(FATAL_ERROR "${what}: no rel_rmse in\n${o}")
  endif()
  set(score ${CMAKE_MATCH_1})
  if(score GREATER ${bound})
    message(FATAL_ERROR "${what}: rel_rmse ${score} > ${bound}\n${o}")
  endif()
  message(STATUS "${what}: rel_rmse ${score} (bound ${bound})")
endfunction()
