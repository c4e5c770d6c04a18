# End to end through the `relight` binary: bad input gives exit code 2 and one clear line
# naming the file and the key, and the output file already there is left as it was (no
# half-written or replaced picture); an edit whose relit image is not finite is such bad
# input, and so is a bad command-line option. Also: the preparation switches
# --no-refinement and --no-shadow-removal reach the report and the cache key. Run by ctest:
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P this
include("${CMAKE_CURRENT_LIST_DIR}/common.cmake")

file(REMOVE_RECURSE "${WORK}")
set(room "${WORK}/room")
# A fresh copy of the room for each case, so one case's damage cannot hide another's.
function(fresh_room)
  copy_room("${room}")
endfunction()
# Cheap settings: the test checks messages and files, not the picture.
set(cheap --epsilon 1e-3 --spp 2 --no-cache)

# The output already there: every failing render below must leave it byte for byte.
set(output "${WORK}/out.png")
file(WRITE "${output}" "an earlier picture")
file(SHA256 "${output}" output_hash)

# Runs a render that must fail with exit code 2 and a message matching `regex`, and
# checks that the output file is untouched and no temporary file is left beside it.
function(expect_failure what regex)
  relight(out 2 render "${room}" ${cheap} ${ARGN} -o "${output}")
  expect("${out}" "error: ${regex}" "${what}")
  file(SHA256 "${output}" h)
  if(NOT h STREQUAL output_hash)
    message(FATAL_ERROR "${what}: the output file was changed")
  endif()
  file(GLOB leftovers "${WORK}/.tmp-*")
  if(leftovers)
    message(FATAL_ERROR "${what}: temporary files left: ${leftovers}")
  endif()
endfunction()

function(set_scene_json member value)
  file(READ "${room}/scene.json" json)
  string(JSON json SET "${json}" ${member} "${value}")
  file(WRITE "${room}/scene.json" "${json}")
endfunction()

# The photo: missing, unreadable, of another size than the camera.
fresh_room()
file(REMOVE "${room}/photo.exr")
expect_failure("missing photo" "[^\n]*room/photo\\.exr: file not found")
fresh_room()
file(WRITE "${room}/photo.exr" "not an image")
expect_failure("unreadable photo" "[^\n]*room/photo\\.exr: cannot read image")
fresh_room()
set_scene_json("camera;width" "160")
expect_failure("photo size" "[^\n]*room/photo\\.exr: photo is 320x240 but the camera is 160x240")

# scene.json: a photo naming an unknown light, a negative radiance.
fresh_room()
set_scene_json("photos;0;lights_on" "[\"A\", \"Q\"]")
expect_failure("unknown light in lights_on" "[^\n]*scene\\.json[^\n]*photos\\[0\\]\\.lights_on[^\n]*Q")
fresh_room()
set_scene_json("lights;1;radiance" "[1, -2, 1]")
expect_failure("negative radiance" "[^\n]*scene\\.json[^\n]*lights\\[1\\]\\.radiance")

# Edits: an unknown light, an unknown key, a missing file.
fresh_room()
file(WRITE "${WORK}/unknown_light.json"
     "{\"format\": \"relight-edit/1\", \"lights\": {\"Z\": {\"on\": false}}}")
expect_failure("edit naming an unknown light" "[^\n]*unknown_light\\.json: key \"lights\\.Z\"[^\n]*unknown light"
               --edit "${WORK}/unknown_light.json")
file(WRITE "${WORK}/unknown_key.json"
     "{\"format\": \"relight-edit/1\", \"lights\": {\"A\": {\"scale\": 2, \"hue\": 1}}}")
expect_failure("edit with an unknown key" "[^\n]*unknown_key\\.json[^\n]*hue"
               --edit "${WORK}/unknown_key.json")
expect_failure("missing edit" "[^\n]*missing\\.json" --edit "${WORK}/missing.json")

# Edits whose relit image is not finite: a scale that overflows the radiance (refused at
# load, before the preparation), a finite radiance that overflows the image's floats.
file(WRITE "${WORK}/huge_scale.json"
     "{\"format\": \"relight-edit/1\", \"lights\": {\"A\": {\"scale\": 1e308}}}")
expect_failure("edit with a scale that overflows"
               "[^\n]*huge_scale\\.json: key \"lights\\.A\\.scale\": the relit image is not finite"
               --edit "${WORK}/huge_scale.json")
file(WRITE "${WORK}/huge_radiance.json"
     "{\"format\": \"relight-edit/1\", \"lights\": {\"B\": {\"radiance\": [1e300, 1, 1]}}}")
expect_failure("edit whose image overflows"
               "[^\n]*huge_radiance\\.json: key \"lights\\.B\\.radiance\": the relit image is not finite"
               --edit "${WORK}/huge_radiance.json")

# The preparation switches: in the report, and a different cache key (so a cache prepared
# with the full method is never used for the 1997 method).
fresh_room()
set(fast --epsilon 1e-3 --spp 2)
relight(out 0 prepare "${room}" ${fast})
relight(out 0 render "${room}" ${fast} --no-refinement --no-shadow-removal -o "${WORK}/a.png"
        --report "${WORK}/a.json")
expect("${out}" "cache stale: inputs changed" "render with --no-shadow-removal after prepare")
file(READ "${WORK}/a.json" json)
string(JSON removal GET "${json}" shadow_removal)
string(JSON refinement GET "${json}" shadow_refinement)
if(NOT removal STREQUAL "OFF" OR NOT refinement STREQUAL "OFF")
  message(FATAL_ERROR "report: shadow_removal ${removal}, shadow_refinement ${refinement}")
endif()

# Bad command-line options: exit code 2, as for any bad input (not CLI11's own codes: 105
# for a value that fails its check, 106 for a missing option), one line that names the
# option, and the output left as it was; --help still exits 0.
function(expect_option_error what regex)
  relight(out 2 ${ARGN})
  expect("${out}" "^error: ${regex}[^\n]*\n$" "${what}")
  file(SHA256 "${output}" h)
  if(NOT h STREQUAL output_hash)
    message(FATAL_ERROR "${what}: the output file was changed")
  endif()
endfunction()
expect_option_error("a value that fails its check" "--epsilon: must be a finite number > 0, got abc"
                    solve "${room}" --epsilon abc)
expect_option_error("a value out of range" "--spp: " render "${room}" --spp 0 -o "${output}")
# NaN passes every comparison-based check (CLI11's PositiveNumber); a negative count would
# wrap to 2^64 - 5 links, that is no budget at all.
expect_option_error("NaN for a threshold" "--epsilon: must be a finite number > 0, got nan"
                    render "${room}" --epsilon nan -o "${output}")
expect_option_error("a negative count" "--max-links: must be a whole number >= 0, got -5"
                    solve "${room}" --max-links -5)
expect_option_error("a negative count (render)" "--max-links: must be a whole number >= 0, got -5"
                    render "${room}" --max-links -5 -o "${output}")
# A time budget must be a finite number of seconds >= 0 (0: none): a negative or NaN
# budget would stop every phase at once or never.
expect_option_error("a negative time budget" "--time-budget: must be a finite number >= 0, got -1"
                    prepare "${room}" --time-budget -1)
expect_option_error("a time budget that is not a number"
                    "--time-budget: must be a finite number >= 0, got 1min"
                    render "${room}" --time-budget 1min -o "${output}")
expect_option_error("NaN for a time budget" "--time-budget: must be a finite number >= 0, got nan"
                    solve "${room}" --time-budget nan)
expect_option_error("a missing option" "--output is required" render "${room}")
expect_option_error("an unknown option" "[^\n]*--no-such-option"
                    render "${room}" --no-such-option -o "${output}")
expect_option_error("options that exclude each other" "--cache excludes --no-cache"
                    render "${room}" --cache "${WORK}/c.bin" --no-cache -o "${output}")
expect_option_error("an unknown command" "unknown command \"rendr\"" rendr "${room}")
expect_option_error("no command" "A subcommand is required")
relight(out 0 --help)
expect("${out}" "render" "relight --help")
relight(out 0 render --help)
expect("${out}" "--edit" "relight render --help")

file(REMOVE_RECURSE "${WORK}")
