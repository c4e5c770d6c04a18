# End to end through the `relight` binary: prepare writes the cache, render uses it, a
# changed option or a corrupt file makes render prepare again, a cache that cannot be
# written does not stop render. Run by ctest (tests/CMakeLists.txt):
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P this
include("${CMAKE_CURRENT_LIST_DIR}/common.cmake")

file(REMOVE_RECURSE "${WORK}")
set(room "${WORK}/room")
copy_room("${room}")
set(cache "${room}/.relight/prepared.bin")
# Cheap settings: the test checks the cache, not the picture.
set(cheap --epsilon 1e-3 --spp 4)

function(report_cache file out)
  file(READ "${file}" json)
  string(JSON value GET "${json}" cache)
  set(${out} "${value}" PARENT_SCOPE)
endfunction()

# prepare: no cache yet, so it prepares and writes one.
relight(out 0 prepare "${room}" ${cheap})
expect("${out}" "no cache at" "first prepare")
expect("${out}" "wrote cache [^\n]*prepared\\.bin" "first prepare")
expect("${out}" "leaves [0-9]+, links [0-9]+, leaf vertices [0-9]+" "first prepare")
# The room fits far within the default budget: the line says so, without "REACHED".
expect("${out}" "budget: [0-9.]+ of [0-9.]+ MiB, links within [0-9]+\n" "first prepare")
if(NOT EXISTS "${cache}")
  message(FATAL_ERROR "prepare wrote no ${cache}")
endif()
# prepare again: nothing to do.
relight(out 0 prepare "${room}" ${cheap})
expect("${out}" "cache up to date" "second prepare")

# render with the same options: a hit.
relight(out 0 render "${room}" ${cheap} -o "${WORK}/a.png" --report "${WORK}/a.json")
expect("${out}" "using cache [^\n]*prepared\\.bin" "render after prepare")
report_cache("${WORK}/a.json" c)
expect("${c}" "^hit$" "report of a hit")
# The budget travels with the cache: the report of a hit still says what the solve used.
file(READ "${WORK}/a.json" json)
string(JSON reached GET "${json}" budget reached)
string(JSON solverMiB GET "${json}" budget solver_mib)
expect("${reached}" "^(OFF|false)$" "report's budget.reached")
if(NOT solverMiB GREATER 0)
  message(FATAL_ERROR "report's budget.solver_mib is ${solverMiB}, expected > 0")
endif()

# Another option: stale, prepared again; then the second render uses the new cache.
relight(out 0 render "${room}" --epsilon 1e-3 --spp 2 -o "${WORK}/b.png" --report "${WORK}/b.json")
expect("${out}" "cache stale: inputs changed" "render with another --spp")
report_cache("${WORK}/b.json" c)
expect("${c}" "^rebuilt: cache stale" "report of a rebuild")
relight(out 0 render "${room}" --epsilon 1e-3 --spp 2 -o "${WORK}/c.exr")
expect("${out}" "using cache" "second render with another --spp")

# A corrupt cache: rebuilt, never trusted.
file(WRITE "${cache}" "RLPREP\r\n garbage")
relight(out 0 render "${room}" --epsilon 1e-3 --spp 2 -o "${WORK}/d.png")
expect("${out}" "cache (truncated|corrupt)" "render with a corrupt cache")
relight(out 0 render "${room}" --epsilon 1e-3 --spp 2 -o "${WORK}/d.png")
expect("${out}" "using cache" "render after the corrupt cache was rebuilt")

# A cache that cannot be written: render warns and goes on; prepare fails naming it, with
# the exit code of any output that cannot be written (tests/cli/write_failures.cmake).
file(WRITE "${WORK}/blocker" "a file where a folder should be")
set(unwritable "${WORK}/blocker/prepared.bin")
relight(out 0 render "${room}" --epsilon 1e-3 --spp 2 --cache "${unwritable}" -o "${WORK}/e.png")
expect("${out}" "warning: [^\n]*blocker/prepared\\.bin: cannot write the cache" "unwritable cache")
if(NOT EXISTS "${WORK}/e.png")
  message(FATAL_ERROR "render wrote no image when the cache could not be written")
endif()
relight(out 3 prepare "${room}" --epsilon 1e-3 --spp 2 --cache "${unwritable}")
expect("${out}" "error: [^\n]*blocker/prepared\\.bin: cannot write the cache" "prepare, unwritable")

# --no-cache: neither read nor written.
relight(out 0 render "${room}" --epsilon 1e-3 --spp 2 --no-cache -o "${WORK}/f.png"
        --report "${WORK}/f.json")
expect_not("${out}" "using cache" "--no-cache")
report_cache("${WORK}/f.json" c)
expect("${c}" "^disabled$" "report with --no-cache")

# --display-pixels changes the display's vertices: 0 keeps the leaf corners only, the
# default (4) adds the corners of the pieces of the leaves that cover 4 pixels or more.
# The room's leaves cover about 20 pixels each, so there are more vertices than leaves.
relight(out 0 prepare "${room}" ${cheap} --display-pixels 0 --force --cache "${WORK}/dp.bin")
string(REGEX MATCH "leaves ([0-9]+), links [0-9]+, leaf vertices ([0-9]+)" m "${out}")
set(corners ${CMAKE_MATCH_2})
relight(out 0 prepare "${room}" ${cheap} --force --cache "${WORK}/dp.bin")
string(REGEX MATCH "leaves ([0-9]+), links [0-9]+, leaf vertices ([0-9]+)" m "${out}")
if(NOT CMAKE_MATCH_2 GREATER corners OR NOT CMAKE_MATCH_2 GREATER CMAKE_MATCH_1)
  message(FATAL_ERROR "--display-pixels: ${CMAKE_MATCH_2} vertices by default, ${corners} "
                      "with 0, for ${CMAKE_MATCH_1} leaves")
endif()

# Numeric options that are not finite (or out of range) are refused, naming the option:
# NaN passes plain range checks, and --epsilon nan used to refine nothing, silently.
foreach(bad "--display-pixels;nan" "--display-pixels;inf" "--display-pixels;-1"
        "--epsilon;nan" "--epsilon;0" "--max-memory;inf")
  list(GET bad 0 option)
  execute_process(COMMAND "${RELIGHT}" prepare "${room}" ${bad}
                  OUTPUT_VARIABLE o ERROR_VARIABLE e RESULT_VARIABLE rc)
  if(rc EQUAL 0)
    message(FATAL_ERROR "${bad}: accepted")
  endif()
  expect("${o}${e}" "${option}: must be a finite number" "${bad}")
endforeach()
execute_process(COMMAND "${RELIGHT}" render "${room}" --exposure nan -o "${WORK}/nan.png"
                OUTPUT_VARIABLE o ERROR_VARIABLE e RESULT_VARIABLE rc)
expect("${o}${e}" "--exposure: must be a finite number" "--exposure nan")
if(rc EQUAL 0 OR EXISTS "${WORK}/nan.png")
  message(FATAL_ERROR "--exposure nan: accepted (exit ${rc})")
endif()

# A bad edit fails at once, before any preparation, naming the file.
relight(out 2 render "${room}" --edit "${WORK}/missing-edit.json" -o "${WORK}/g.png")
expect("${out}" "missing-edit\\.json" "bad edit")
expect_not("${out}" "preparing|using cache" "bad edit")

# The per-pixel display renders an edit with virtual parts (a light and a box), and says
# what it inserted.
relight(out 0 render "${room}" ${cheap} --no-cache --display pixel
        --edit "${SCENE}/edits/virtual_light_and_box.json" -o "${WORK}/pixel_virtual.exr")
expect("${out}" "inserted light [^\n]*\ninserted object box" "pixel display, virtual parts")
if(NOT EXISTS "${WORK}/pixel_virtual.exr")
  message(FATAL_ERROR "render --display pixel wrote no image for virtual_light_and_box")
endif()

file(REMOVE_RECURSE "${WORK}")
