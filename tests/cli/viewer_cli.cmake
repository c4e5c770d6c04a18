# relight-viewer end to end, under a virtual X server with Mesa's llvmpipe:
#  - in the per-pixel display (the viewer's default, render's) and in the ratio display
#    (--display ratio, on the GPU), the screenshot of each room light edit, a session by
#    clicks (a lamp, a box dragged), a removal and its restore are render's within one step;
#  - the screenshot of each room light edit is `relight render`'s PNG within one 8-bit step
#    (the GPU sums in float what the CPU sums in double: only values within about 1e-6 of a
#    rounding boundary change, by one step; tests/viewer/viewer_test.cpp bounds the rest);
#  - a session built by clicks (a light, a box, a drag) saved as an edit renders through
#    `relight render` to the viewer's screenshot within the same step;
#  - a real object removed by a click, saved, renders the same; brought back, the photo;
#    the cabinet against two walls likewise, brought back bit for bit;
#  - real lamps placed by clicks are saved into scene.json, which renders with them;
#  - the window with its panel opens and draws;
#  - clear messages and no output for a missing display, an OpenGL older than 3.3, a scene
#    or edit that does not load, an edit whose display is not finite, a bad option or --do.
# All at the coarse preparation (viewer_common.cmake's ${coarse}), the viewer's and render's
# alike: what is checked is that both draw the same, at any preparation.
# Run as cmake -DVIEWER=... -DRELIGHT=... -DXVFB_RUN=... -DSCENE=data/room -DWORK=... -P this
# (and -DVIEWER_PRELOAD=... under the sanitizers: tests/CMakeLists.txt says why).
include(${CMAKE_CURRENT_LIST_DIR}/viewer_common.cmake)
set(cache "${WORK}/prepared.bin")

# With --display ratio the viewer shows the ratio display (Loscos et al. 2000) on the GPU;
# render is asked for the same display, prepared the viewer's way (no per-pixel light), so
# both share the cache. The viewer's default is render's (per pixel), checked further down.
set(as_viewer --display ratio --no-pixel-light)
foreach(edit identity back_off left_off_right_double right_off_left_double colours)
  render(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/${edit}.json"
         -o "${WORK}/${edit}_render.png" --cache "${cache}" ${as_viewer})
  viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/${edit}.json" --display ratio
         --screenshot "${WORK}/${edit}_viewer.png")
  expect("${o}" "wrote .*${edit}_viewer.png \\(320x240, float framebuffer" "screenshot ${edit}")
  same_within_one_step("${WORK}/${edit}_viewer.png" "${WORK}/${edit}_render.png" "edit ${edit}")
endforeach()

# Exposure is applied as render applies it (before the sRGB transfer function).
render(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/back_off.json"
       -o "${WORK}/exposed_render.png" --cache "${cache}" --exposure 1.5 ${as_viewer})
viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/back_off.json" --display ratio
       --exposure 1.5 --screenshot "${WORK}/exposed_viewer.png")
same_within_one_step("${WORK}/exposed_viewer.png" "${WORK}/exposed_render.png" "exposure 1.5")

# A session by clicks: a lamp on the ceiling, a box on the floor dragged 60 pixels along it.
set(saved "${WORK}/saved/session.json")
file(MAKE_DIRECTORY "${WORK}/saved")
viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/back_off.json" --display ratio
       --do light:200,20 --do box:90,200 --do drag:90,195:150,210 --save-edit "${saved}"
       --screenshot "${WORK}/session_viewer.png")
file(READ "${saved}" json)
expect("${json}" "\"add_lights\"" "saved session")
expect("${json}" "\"file\": \"session.box.obj\"" "saved session")
if(NOT EXISTS "${WORK}/saved/session.box.obj")
  message(FATAL_ERROR "the saved session's box OBJ is missing")
endif()
render(o 0 "${SCENE}" ${coarse} --edit "${saved}" -o "${WORK}/session_render.png"
       --cache "${cache}" ${as_viewer})
expect("${o}" "inserted object box1" "render of the saved session")
same_within_one_step("${WORK}/session_viewer.png" "${WORK}/session_render.png" "saved session")

# The per-pixel display (the direct light per pixel, drawn on the CPU) is the viewer's
# default, as it is render's: every light edit of the room, a session by clicks (a lamp
# added, a box inserted and dragged) whose saved edit render draws with its virtual parts per
# pixel, a removal, and a removal brought back (the photo's display again).
foreach(edit identity back_off left_off_right_double right_off_left_double colours)
  render(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/${edit}.json"
         -o "${WORK}/pixel_${edit}_render.png" --cache "${WORK}/pixel.bin")
  viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/${edit}.json"
         --screenshot "${WORK}/pixel_${edit}_viewer.png")
  same_within_one_step("${WORK}/pixel_${edit}_viewer.png" "${WORK}/pixel_${edit}_render.png"
                       "per-pixel display (default), edit ${edit}")
endforeach()
file(MAKE_DIRECTORY "${WORK}/pixel_saved")
viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/back_off.json" --do light:200,20
       --do box:90,200 --do drag:90,195:150,210 --save-edit "${WORK}/pixel_saved/session.json"
       --screenshot "${WORK}/pixel_session_viewer.png")
render(o 0 "${SCENE}" ${coarse} --edit "${WORK}/pixel_saved/session.json"
       -o "${WORK}/pixel_session_render.png" --cache "${WORK}/pixel.bin")
same_within_one_step("${WORK}/pixel_session_viewer.png" "${WORK}/pixel_session_render.png"
                     "per-pixel display, saved session")
# Real-object removal (Loscos et al. 1999, §5.3) by a click on the table: the saved edit
# names it and renders to the screenshot, in the ratio display (the GPU's) and per pixel;
# brought back from the panel, the photo's display again.
file(MAKE_DIRECTORY "${WORK}/removal")
viewer(o 0 "${SCENE}" ${coarse} --display ratio --do remove:180,155
       --save-edit "${WORK}/removal/edit.json" --screenshot "${WORK}/removal_viewer.png")
file(READ "${WORK}/removal/edit.json" json)
expect("${json}" "\"remove_objects\": \\[[^]]*\"table\"" "saved removal")
render(o 0 "${SCENE}" ${coarse} --edit "${WORK}/removal/edit.json"
       -o "${WORK}/removal_render.png" --cache "${cache}" ${as_viewer})
expect("${o}" "removed object table: [0-9]+ links cut, [0-9]+ pixels filled" "render of the removal")
same_within_one_step("${WORK}/removal_viewer.png" "${WORK}/removal_render.png" "removal")
viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/remove_table.json"
       --screenshot "${WORK}/pixel_removal_viewer.png")
render(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/remove_table.json"
       -o "${WORK}/pixel_removal_render.png" --cache "${WORK}/pixel.bin")
same_within_one_step("${WORK}/pixel_removal_viewer.png" "${WORK}/pixel_removal_render.png"
                     "per-pixel display, removal")
viewer(o 0 "${SCENE}" ${coarse} --do remove:180,155 --do restore:table
       --screenshot "${WORK}/pixel_restored.png")
same_within_one_step("${WORK}/pixel_restored.png" "${WORK}/pixel_identity_render.png"
                     "per-pixel display, table brought back")
viewer(o 0 "${SCENE}" ${coarse} --display ratio --do remove:180,155 --do restore:table
       --screenshot "${WORK}/restored.png")
same_within_one_step("${WORK}/restored.png" "${WORK}/identity_render.png" "table brought back")
# The cabinet against two walls (issue 34): its first frame in the viewer (per pixel) is
# render's; removed by a click and brought back, the viewer's photo display bit for bit.
viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/remove_cabinet.json"
       --screenshot "${WORK}/pixel_cabinet_viewer.png")
render(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/remove_cabinet.json"
       -o "${WORK}/pixel_cabinet_render.png" --cache "${WORK}/pixel.bin")
same_within_one_step("${WORK}/pixel_cabinet_viewer.png" "${WORK}/pixel_cabinet_render.png"
                     "per-pixel display, cabinet removed")
viewer(o 0 "${SCENE}" ${coarse} --display ratio --screenshot "${WORK}/photo_viewer.png")
viewer(o 0 "${SCENE}" ${coarse} --display ratio --do remove:118,140 --do restore:cabinet
       --screenshot "${WORK}/cabinet_restored.png")
execute_process(COMMAND "${IDIFF}" -fail 0 -failpercent 0 "${WORK}/cabinet_restored.png"
                "${WORK}/photo_viewer.png" OUTPUT_VARIABLE o ERROR_VARIABLE e RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cabinet brought back: not the photo's display bit for bit\n${o}${e}")
endif()
viewer(o 2 "${SCENE}" --display ratio --do remove:250,60 --screenshot "${WORK}/never.png")
expect("${o}" "remove:250,60: no removable real object at that pixel" "removal of a wall")
viewer(o 2 "${SCENE}" --display ratio --do restore:table --screenshot "${WORK}/never.png")
expect("${o}" "\"table\" is not taken out" "restoring what is there")
viewer(o 2 "${SCENE}" --display vertex --screenshot "${WORK}/never.png")
expect("${o}" "--display" "a display that does not exist")

# Real lamps placed by clicks on the photo (--do lamp) and saved into a copy of the room's
# scene.json as the format's quad lights, their radiance estimated from the photo; the
# scene then renders with them.
copy_room("${WORK}/lamps")
viewer(o 0 "${WORK}/lamps" ${coarse} --display ratio --do lamp:160,20:0.3,0.2 --do lamp:60,120
       --save-lamps --screenshot "${WORK}/lamps.png")
expect("${o}" "added 2 lamps to [^\n]*lamps/scene.json" "lamps saved")
file(READ "${WORK}/lamps/scene.json" json)
string(JSON count LENGTH "${json}" lights)
string(JSON name GET "${json}" lights 4 name)
string(JSON radiance GET "${json}" lights 4 radiance)
string(JSON on GET "${json}" photos 0 lights_on 5)
if(NOT count EQUAL 6 OR NOT name STREQUAL "L1" OR NOT radiance STREQUAL "estimate"
   OR NOT on STREQUAL "L2")
  message(FATAL_ERROR "saved lamps: ${count} lights, ${name}, ${radiance}, ${on}:\n${json}")
endif()
render(o 0 "${WORK}/lamps" ${coarse} --no-cache -o "${WORK}/lamps_render.png")
expect("${o}" "light \"L1\": [^\n]* from [0-9]+ photo pixels on its face" "render with the lamps")
viewer(o 2 "${SCENE}" --display ratio --do lamp:160,20:0,1 --screenshot "${WORK}/never.png")
expect("${o}" "--do lamp:160,20:0,1: the size must be positive" "a lamp of no size")

# The window itself, panel included.
viewer(o 0 "${SCENE}" ${coarse} --window-screenshot "${WORK}/window.png")
expect("${o}" "wrote .*window.png \\([0-9]+x[0-9]+\\)" "window screenshot")

# Failures: a message, a non-zero exit code, and an existing output left as it was.
file(WRITE "${WORK}/keep.png" "not an image, and it must stay so")
execute_process(COMMAND "${CMAKE_COMMAND}" -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY
                        ${viewer_cmd} "${SCENE}" --screenshot "${WORK}/keep.png"
                ERROR_VARIABLE e RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT e MATCHES "no display: DISPLAY is not set")
  message(FATAL_ERROR "without a display: exit code ${rc}, message:\n${e}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env MESA_GL_VERSION_OVERRIDE=3.0
                        "${XVFB_RUN}" -a ${viewer_cmd} "${SCENE}" --screenshot "${WORK}/keep.png"
                ERROR_VARIABLE e RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT e MATCHES "no OpenGL 3.3 core context")
  message(FATAL_ERROR "with OpenGL 3.0 only: exit code ${rc}, message:\n${e}")
endif()
viewer(o 2 "${WORK}/no_such_scene" --screenshot "${WORK}/keep.png")
expect("${o}" "no_such_scene/scene.json" "missing scene")
file(WRITE "${WORK}/bad_edit.json" "{\"format\": \"relight-edit/1\", \"lights\": {\"Q\": {\"scale\": 2}}}")
viewer(o 2 "${SCENE}" --edit "${WORK}/bad_edit.json" --screenshot "${WORK}/keep.png")
expect("${o}" "bad_edit.json: key \"lights.Q\"" "bad edit")
# A finite radiance whose display overflows the floats: refused, naming the edit's key.
file(WRITE "${WORK}/huge_edit.json"
     "{\"format\": \"relight-edit/1\", \"lights\": {\"B\": {\"radiance\": [1e300, 1, 1]}}}")
viewer(o 2 "${SCENE}" --edit "${WORK}/huge_edit.json" --epsilon 1e-3 --spp 2
       --screenshot "${WORK}/keep.png")
expect("${o}" "huge_edit.json: key \"lights.B.radiance\": the relit image is not finite"
       "edit whose display overflows")
# A bad option: exit code 2 as for any bad input (not CLI11's 105), one line naming it.
viewer(o 2 "${SCENE}" --spp 0 --screenshot "${WORK}/keep.png")
expect("${o}" "^relight-viewer: error: --spp: [^\n]*\n$" "bad option")
# NaN passes CLI11's PositiveNumber (every comparison with NaN is false).
viewer(o 2 "${SCENE}" --epsilon nan --screenshot "${WORK}/keep.png")
expect("${o}" "^relight-viewer: error: --epsilon: must be a finite number > 0, got nan; see[^\n]*\n$"
       "NaN epsilon")
viewer(o 2 "${SCENE}" --exposure inf --screenshot "${WORK}/keep.png")
expect("${o}" "^relight-viewer: error: --exposure: must be a finite number, got inf; see[^\n]*\n$"
       "infinite exposure")
viewer(o 2 "${SCENE}" --time-budget -1 --screenshot "${WORK}/keep.png")
expect("${o}" "^relight-viewer: error: --time-budget: must be a finite number >= 0, got -1; see"
       "negative time budget")
# The budget reaches the preparation: its phases past their share say so (the viewer's image
# is then not render's, hence the others' --time-budget 0).
viewer(o 0 "${SCENE}" --epsilon 1e-3 --spp 2 --time-budget 0.01 --screenshot "${WORK}/hurried.png")
expect("${o}" "warning: [^\n]*its share of --time-budget" "a time budget of 0.01 s")
viewer(o 0 --help)
expect("${o}" "--screenshot" "--help")
viewer(o 2 "${SCENE}" --do light:abc --screenshot "${WORK}/keep.png")
expect("${o}" "--do light:abc" "bad action")
file(READ "${WORK}/keep.png" kept)
if(NOT kept STREQUAL "not an image, and it must stay so")
  message(FATAL_ERROR "a failed run changed an existing output file")
endif()
message(STATUS "viewer end to end: all checks passed")
