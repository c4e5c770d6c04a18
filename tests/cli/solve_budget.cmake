# End to end through the `relight` binary: `relight solve`'s reflectance estimate and its
# time budget. With a budget spent before the estimate could begin, the solve still ends with
# its image and report, says the reflectance was not estimated, and the report has
# reflectance.skipped; with the default budget the room's estimate runs (rounds >= 1, not
# skipped). Run by ctest (tests/CMakeLists.txt):
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P this
include("${CMAKE_CURRENT_LIST_DIR}/common.cmake")

file(REMOVE_RECURSE "${WORK}")
set(room "${WORK}/room")
copy_room("${room}")

# 50 ms: spent by the time the refinement ends, on any machine.
relight(out 0 solve "${room}" --epsilon 1e-3 --time-budget 0.05 -o "${WORK}/late.exr"
        --report "${WORK}/late.json")
expect("${out}" "warning: the reflectance was not estimated" "solve --time-budget 0.05")
expect("${out}" "wrote [^\n]*late.exr" "solve --time-budget 0.05")
file(READ "${WORK}/late.json" json)
string(JSON skipped GET "${json}" reflectance skipped)
string(JSON rounds GET "${json}" reflectance rounds)
if(NOT skipped STREQUAL "ON" OR NOT rounds EQUAL 0)
  message(FATAL_ERROR "late solve: reflectance.skipped ${skipped}, rounds ${rounds}")
endif()

relight(out 0 solve "${room}" --epsilon 1e-3 --report "${WORK}/whole.json")
expect_not("${out}" "reflectance was not estimated" "solve at the default budget")
file(READ "${WORK}/whole.json" json)
string(JSON skipped GET "${json}" reflectance skipped)
string(JSON rounds GET "${json}" reflectance rounds)
if(NOT skipped STREQUAL "OFF" OR rounds LESS 1)
  message(FATAL_ERROR "solve: reflectance.skipped ${skipped}, rounds ${rounds}")
endif()
