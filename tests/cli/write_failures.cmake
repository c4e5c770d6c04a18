# End to end through the `relight` binary: an output that cannot be written fails with one
# exit code, 3 (relight/errors.h), whichever output it is: the prepared-state cache, the
# relit image, the report, the solve's image. The message names the file, an existing
# file is left as it was, and no temporary file is left beside it. Run by ctest:
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P this
include("${CMAKE_CURRENT_LIST_DIR}/common.cmake")

file(REMOVE_RECURSE "${WORK}")
set(room "${WORK}/room")
copy_room("${room}")
# Cheap settings: the test checks exit codes, messages and files, not the picture.
set(cheap --epsilon 1e-3 --spp 2)
set(out "${WORK}/out")
file(MAKE_DIRECTORY "${out}")
# Two ways a write fails: the folder is a file (the temporary file cannot be made), and
# the target is a folder (the temporary file is written, the rename fails).
file(WRITE "${WORK}/blocker" "a file where a folder should be")
set(blocked "${WORK}/blocker")

# Checks that `dir` holds no temporary file.
function(expect_no_temporary dir what)
  file(GLOB leftovers "${dir}/.tmp-*")
  if(leftovers)
    message(FATAL_ERROR "${what}: temporary files left: ${leftovers}")
  endif()
endfunction()

# The cache, written by prepare.
relight(o 3 prepare "${room}" ${cheap} --cache "${blocked}/prepared.bin")
expect("${o}" "error: [^\n]*blocker/prepared\\.bin: cannot write the cache" "cache, folder a file")
file(MAKE_DIRECTORY "${out}/cache.bin")
relight(o 3 prepare "${room}" ${cheap} --cache "${out}/cache.bin")
expect("${o}" "error: [^\n]*out/cache\\.bin: cannot write the cache" "cache, target a folder")
expect_no_temporary("${out}" "cache")

# A valid cache for the renders below, so that they fail at writing and nothing else.
set(cache "${WORK}/prepared.bin")
relight(o 0 prepare "${room}" ${cheap} --cache "${cache}")

# The relit image.
relight(o 3 render "${room}" ${cheap} --cache "${cache}" -o "${blocked}/a.png")
expect("${o}" "error: [^\n]*blocker/a\\.png: cannot write image" "image, folder a file")
file(MAKE_DIRECTORY "${out}/b.exr")
relight(o 3 render "${room}" ${cheap} --cache "${cache}" -o "${out}/b.exr")
expect("${o}" "error: [^\n]*out/b\\.exr: cannot write image" "image, target a folder")
expect_no_temporary("${out}" "image")

# The report: the image is written, the report is not, and an earlier report stays.
relight(o 3 render "${room}" ${cheap} --cache "${cache}" -o "${out}/c.png"
        --report "${blocked}/c.json")
expect("${o}" "error: [^\n]*blocker/c\\.json: cannot write" "report")

# The solve's image.
relight(o 3 solve "${room}" --epsilon 1e-2 --spp 1 --no-photo-reflectance
        -o "${blocked}/radiosity.png")
expect("${o}" "error: [^\n]*blocker/radiosity\\.png: cannot write image" "solve's image")

# An existing output is left as it was when it cannot be replaced.
file(WRITE "${out}/keep.json" "an earlier report")
file(MAKE_DIRECTORY "${out}/.tmp-keep.json")  # the temporary file's name is taken
relight(o 3 render "${room}" ${cheap} --cache "${cache}" -o "${out}/d.png"
        --report "${out}/keep.json")
expect("${o}" "error: [^\n]*out/keep\\.json: cannot write" "report over an earlier one")
file(READ "${out}/keep.json" kept)
if(NOT kept STREQUAL "an earlier report")
  message(FATAL_ERROR "a failed write changed the earlier report")
endif()

file(REMOVE_RECURSE "${WORK}")
