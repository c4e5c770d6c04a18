# End to end through the `relight` binary: the room's camera exported as a COLMAP model
# (text and binary) and imported back with its photo, mesh, lights and objects gives the
# same scene.json from either form, and relights exactly like the room (the same scores,
# digit for digit); bad inputs are exit code 2 with one line naming the file and line, and
# leave the output folder unwritten. Run by ctest (tests/CMakeLists.txt):
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P this
include("${CMAKE_CURRENT_LIST_DIR}/common.cmake")

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/images")
file(COPY_FILE "${SCENE}/photo.exr" "${WORK}/images/photo.exr")

relight(out 0 export colmap "${SCENE}" -o "${WORK}/sparse_txt")
expect("${out}" "camera 1 \\(PINHOLE 320x240\\), image 1 \"photo.exr\"" "export text")
relight(out 0 export colmap "${SCENE}" -o "${WORK}/sparse_bin" --binary)
file(READ "${WORK}/sparse_txt/cameras.txt" cameras)
# COLMAP's principal point: the format's (159.5, 119.5) plus half a pixel.
expect("${cameras}" "\n1 PINHOLE 320 240 170 170 160 120\n" "exported cameras.txt")

set(inputs --image photo.exr --images "${WORK}/images" --mesh "${SCENE}/room.obj"
    --lights "${SCENE}/scene.json" --objects "${SCENE}/scene.json" --average-reflectance 0.6)
foreach(form txt bin)
  relight(out 0 import colmap "${WORK}/sparse_${form}" ${inputs} -o "${WORK}/${form}")
  expect("${out}" "camera PINHOLE, 320x240\nK: fx 170 fy 170 cx 159.5 cy 119.5" "import ${form}")
  expect("${out}" "4 lights\nwrote " "import ${form}")
endforeach()
file(SHA256 "${WORK}/txt/scene.json" txt_hash)
file(SHA256 "${WORK}/bin/scene.json" bin_hash)
if(NOT txt_hash STREQUAL bin_hash)
  message(FATAL_ERROR "the text and binary models gave different scene.json files")
endif()

# The imported room relights as the room: the same scores for an edit that switches the
# left lights off and doubles the right ones. Cheap settings: the test compares, it does not
# score.
set(cheap --epsilon 1e-3 --spp 2 --no-cache)
set(edit "${SCENE}/edits/left_off_right_double.json")
relight(out 0 render "${SCENE}" ${cheap} --edit "${edit}" -o "${WORK}/room.exr")
relight(out 0 render "${WORK}/txt" ${cheap} --edit "${edit}" -o "${WORK}/imported.exr")
relight(room_scores 0 eval "${SCENE}" left_off_right_double "${WORK}/room.exr")
relight(imported_scores 0 eval "${SCENE}" left_off_right_double "${WORK}/imported.exr")
expect("${room_scores}" "rel_rmse [0-9.]+" "eval of the room")
if(NOT room_scores STREQUAL imported_scores)
  message(FATAL_ERROR "the imported room scores differently:\n${room_scores}\n${imported_scores}")
endif()

# Bad input: exit code 2, one line naming the file (and line), nothing written.
function(expect_import_failure what regex)
  relight(out 2 import colmap ${ARGN} -o "${WORK}/failed")
  expect("${out}" "^error: ${regex}[^\n]*\n$" "${what}")
  if(EXISTS "${WORK}/failed")
    message(FATAL_ERROR "${what}: the output folder was written")
  endif()
endfunction()
set(model "${WORK}/bad_model")
function(write_model cameras images)
  file(MAKE_DIRECTORY "${model}")
  file(WRITE "${model}/cameras.txt" "${cameras}")
  file(WRITE "${model}/images.txt" "${images}")
endfunction()
set(pinhole "# cameras\n1 PINHOLE 320 240 170 170 160 120\n")
set(pose "0.5976 0.7205 0.2707 -0.2245 -2.88 1.30 2.54")
set(mesh_and_photo --images "${WORK}/images" --mesh "${SCENE}/room.obj")

write_model("${pinhole}" "# images\n1 ${pose} 1 photo.exr\n\n")
expect_import_failure("a missing image" "[^\n]*bad_model/images\\.txt: no image named \"other\\.exr\""
                      "${model}" --image other.exr ${mesh_and_photo})
write_model("${pinhole}" "# images\n\n1 ${pose} 4 photo.exr\n\n")
expect_import_failure("an undefined camera"
                      "[^\n]*images\\.txt:3: image \"photo\\.exr\" uses camera 4, which [^\n]*cameras\\.txt does not define"
                      "${model}" --image photo.exr ${mesh_and_photo})
write_model("# cameras\n1 PINHOLE 640 480 340 340 320 240\n" "1 ${pose} 1 photo.exr\n\n")
expect_import_failure("a photo of another size"
                      "[^\n]*images/photo\\.exr: photo is 320x240 but its camera \\([^\n]*cameras\\.txt:2\\) is 640x480"
                      "${model}" --image photo.exr ${mesh_and_photo})
write_model("# cameras\n1 OPENCV_FISHEYE 320 240 170 170 160 120 0 0 0 0\n" "1 ${pose} 1 photo.exr\n\n")
expect_import_failure("a camera model that is not taken"
                      "[^\n]*cameras\\.txt:2: camera model OPENCV_FISHEYE is not supported[^\n]*colmap image_undistorter"
                      "${model}" --image photo.exr ${mesh_and_photo})
write_model("${pinhole}" "1 ${pose} 1 photo.exr\n\n")
file(WRITE "${WORK}/broken.obj" "v 0 0 0\nv 1 0 0\nf 1 2 7\n")
expect_import_failure("a mesh that does not load" "[^\n]*broken\\.obj:3: "
                      "${model}" --image photo.exr --images "${WORK}/images" --mesh "${WORK}/broken.obj")

# A folder that is not empty is an output that cannot be written (exit code 3), unless
# --force; either way, what is in it stays.
relight(out 3 import colmap "${WORK}/sparse_txt" ${inputs} -o "${WORK}/txt")
expect("${out}" "error: [^\n]*txt: the folder is not empty \\(--force writes into it\\)" "not empty")
file(WRITE "${WORK}/txt/notes.txt" "mine")
relight(out 0 import colmap "${WORK}/sparse_txt" ${inputs} -o "${WORK}/txt" --force)
file(READ "${WORK}/txt/notes.txt" notes)
if(NOT notes STREQUAL "mine")
  message(FATAL_ERROR "--force changed a file the import does not write")
endif()

file(REMOVE_RECURSE "${WORK}")
