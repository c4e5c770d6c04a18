# relight sky: the courtyard's sky fitted to its photo, printed as an edit that the edit
# loader accepts (render takes it); --photo with the same photo prints the same sky; a
# scene without a sky, and a photo that cannot be read, are refused with exit code 2.
# Run by ctest (tests/CMakeLists.txt):
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P this
include("${CMAKE_CURRENT_LIST_DIR}/common.cmake")

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
get_filename_component(data "${SCENE}" DIRECTORY)
set(court "${WORK}/courtyard")
file(MAKE_DIRECTORY "${court}")
foreach(f scene.json courtyard.obj photo.exr photo.mask.png)
  file(COPY_FILE "${data}/courtyard/${f}" "${court}/${f}")
endforeach()

function(sky_edit out_file)
  execute_process(COMMAND "${RELIGHT}" sky "${court}" --spp 1 ${ARGN}
                  OUTPUT_FILE "${out_file}" ERROR_VARIABLE e RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "relight sky ${ARGN}: exit code ${rc}\n${e}")
  endif()
  expect("${e}" "sky \"sky\" sh9" "relight sky's summary")
endfunction()

sky_edit("${WORK}/sky.json")
file(READ "${WORK}/sky.json" json)
string(JSON format GET "${json}" format)
expect("${format}" "^relight-edit/1$" "the edit's format")
string(JSON rows LENGTH "${json}" lights sky sh9)
expect("${rows}" "^9$" "the sh9 rows")
foreach(k RANGE 8)
  string(JSON n LENGTH "${json}" lights sky sh9 ${k})
  expect("${n}" "^3$" "sh9 row ${k}")
endforeach()
# The edit loader takes it: render the courtyard with it (cheap settings: the test checks
# that the edit is read, not the picture).
relight(out 0 render "${court}" --edit "${WORK}/sky.json" -o "${WORK}/sky.exr" --no-cache
        --epsilon 1e-3 --spp 1 --no-pixel-light --display ratio --no-refinement)

# --photo with a copy of the same photo: the same fit, the same text.
file(COPY_FILE "${court}/photo.exr" "${WORK}/other.exr")
sky_edit("${WORK}/sky2.json" --photo "${WORK}/other.exr")
file(READ "${WORK}/sky2.json" json2)
if(NOT json STREQUAL json2)
  message(FATAL_ERROR "--photo with the same photo printed another sky:\n${json}\n${json2}")
endif()

# Refusals: a missing photo, a scene without an environment light.
relight(out 2 sky "${court}" --photo "${WORK}/none.exr")
expect("${out}" "none\\.exr" "a missing --photo")
copy_room("${WORK}/room")
relight(out 2 sky "${WORK}/room")
expect("${out}" "no light of type \"environment\" to fit" "a scene without a sky")
