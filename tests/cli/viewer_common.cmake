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

# The scripts compare the viewer's image with `relight render`'s pixel by pixel: each runs
# its own preparation, so both run without a time budget (--time-budget 0). Within the
# default 60 s, a phase past its share takes a coarser fallback: on a loaded machine under
# the sanitizers' build one of the two may take it and the other not (the CI of 2026-11-30:
# viewer.slider 85 s, one pixel two 8-bit steps apart), which says nothing of the paths
# under test. tests/cli/solve_budget.cmake and bad_input.cmake test the budget itself.

# A coarse preparation (BF threshold 1e-3, 2 camera samples per pixel) for the scripts that
# check that the viewer draws what `relight render` draws, and that each control runs: the
# same code paths as the default preparation's, at half the time (the room: 8.0 s -> 4.0 s a
# viewer run per pixel, 4.4 s -> 1.9 s in the ratio display). The scripts that score an image
# against the truth keep the default.
set(coarse --epsilon 1e-3 --spp 2)

# `args` gets ARGN with --time-budget 0 after it, unless ARGN gives a --time-budget (the
# programs refuse one given twice).
function(unhurried args)
  set(a ${ARGN})
  if(NOT "--time-budget" IN_LIST a)
    list(APPEND a --time-budget 0)
  endif()
  set(${args} ${a} PARENT_SCOPE)
endfunction()

# `relight render` with the arguments after `expected_rc`, without a time budget.
function(render out expected_rc)
  unhurried(args ${ARGN})
  relight(o ${expected_rc} render ${args})
  set(${out} "${o}" PARENT_SCOPE)
endfunction()

# Runs the viewer under xvfb-run (run_checked), with an X authority file of its own (-f),
# without a time budget.
# xvfb-run still removes a temporary folder at its exit, which can race the X server's reset
# on a loaded machine: it then exits with 5 ("problem while cleaning up temporary
# directory") in place of the viewer's own code (seen in the CI of 2026-11-29, the viewer's
# screenshot written). That exit says nothing of the viewer, so the run is made once more;
# any other code, or a second such exit, is checked as it is.
function(viewer out expected_rc)
  unhurried(args ${ARGN})
  set(cmd "${XVFB_RUN}" -a -f "${WORK}/Xauthority" -s "-screen 0 1280x1024x24" ${viewer_cmd}
      ${args})
  execute_process(COMMAND ${cmd} OUTPUT_VARIABLE o ERROR_VARIABLE e RESULT_VARIABLE rc)
  if(rc EQUAL 5 AND NOT expected_rc EQUAL 5 AND e MATCHES "xvfb-run: error: problem while cleaning up")
    message(STATUS "xvfb-run failed to clean up after the viewer (exit code 5): run again")
  else()
    if(NOT rc EQUAL expected_rc)
      message(FATAL_ERROR "${cmd}: exit code ${rc}, expected ${expected_rc}\n${o}${e}")
    endif()
    set(${out} "${o}${e}" PARENT_SCOPE)
    return()
  endif()
  run_checked(o ${expected_rc} ${cmd})
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
