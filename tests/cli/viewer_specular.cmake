# The specular pass in the viewer (../shared/seeds/000, §6; relight/dynamic/specular.h), on
# data/room:
#  - the bundled edit with a specular box (edits/virtual_box_specular.json): the viewer's
#    screenshot is `relight render`'s within one 8-bit step, in the per-pixel display (the
#    default, drawn on the CPU) and in the ratio display (the GPU's, the term in its overlay);
#  - the term set from the panel (--do specular:NAME:R,G,B:S, what the object's controls do)
#    is saved in the session's edit, which renders to the screenshot within the same step;
#    and it shows: without it the box is not the same image;
#  - a bad --do (ks < 0, shininess <= 0, an object that is not there) is refused, exit 2.
# The viewer and render both at the coarse preparation (viewer_common.cmake's ${coarse}).
# Run as cmake -DVIEWER=... -DRELIGHT=... -DXVFB_RUN=... -DSCENE=data/room -DWORK=... -P this
include(${CMAKE_CURRENT_LIST_DIR}/viewer_common.cmake)
set(edit "${SCENE}/edits/virtual_box_specular.json")

# One 8-bit step, 1/255 = 0.0039 (as viewer_cli.cmake); EXR, linear values.
foreach(display pixel ratio)
  set(extra)
  if(display STREQUAL "ratio")
    set(extra --no-pixel-light)  # prepared as the viewer prepares its ratio display
  endif()
  render(o 0 "${SCENE}" ${coarse} --edit "${edit}" -o "${WORK}/bundled_render_${display}.exr"
          --display ${display} --cache "${WORK}/${display}.bin" ${extra})
  viewer(o 0 "${SCENE}" ${coarse} --edit "${edit}" --display ${display}
         --screenshot "${WORK}/bundled_viewer_${display}.exr")
  same_within("${WORK}/bundled_viewer_${display}.exr" "${WORK}/bundled_render_${display}.exr"
              0.004 "the specular box (${display} display): the viewer against render")
endforeach()

# From the panel: the bundled box without its term, the term set by the object's controls.
file(READ "${edit}" json)
string(REGEX REPLACE ",[ \n]*\"specular\": {[^}]*}" "" json "${json}")
string(REPLACE "../objects/box.obj" "${SCENE}/objects/box.obj" json "${json}")
file(WRITE "${WORK}/matte.json" "${json}")
set(saved "${WORK}/saved/panel.json")
file(MAKE_DIRECTORY "${WORK}/saved")
viewer(o 0 "${SCENE}" ${coarse} --edit "${WORK}/matte.json" --do specular:box:0.3,0.4,0.5:12
       --save-edit "${saved}" --screenshot "${WORK}/panel_viewer.exr")
file(READ "${saved}" json)
expect("${json}" "\"specular\": {[^}]*\"ks\": \\[[^]]*0\\.3,[^]]*0\\.4,[^]]*0\\.5[^]]*\\]"
       "the panel's ks saved in the session's edit")
expect("${json}" "\"shininess\": 12" "the panel's shininess saved in the session's edit")
render(o 0 "${SCENE}" ${coarse} --edit "${saved}" -o "${WORK}/panel_render.exr"
        --cache "${WORK}/pixel.bin")
same_within("${WORK}/panel_viewer.exr" "${WORK}/panel_render.exr" 0.004
            "the term set from the panel: the viewer against render of the saved edit")
# The term shows: the matte box's frame differs from it by more than a step somewhere.
viewer(o 0 "${SCENE}" ${coarse} --edit "${WORK}/matte.json" --screenshot "${WORK}/matte_viewer.exr")
execute_process(COMMAND "${IDIFF}" -fail 0.004 -failpercent 0 "${WORK}/matte_viewer.exr"
                        "${WORK}/panel_viewer.exr" OUTPUT_QUIET ERROR_QUIET RESULT_VARIABLE rc)
if(rc EQUAL 0)
  message(FATAL_ERROR "the specular term set from the panel changed nothing on the screen")
endif()

# Bad values: clear messages, exit code 2.
foreach(bad "box:-0.1,0.2,0.2:8|ks must be >= 0" "box:0.1,0.2,0.2:0|shininess must be > 0"
            "ghost:0.1,0.2,0.2:8|no virtual object \"ghost\"")
  string(REPLACE "|" ";" parts "${bad}")
  list(GET parts 0 action)
  list(GET parts 1 message)
  viewer(o 2 "${SCENE}" --edit "${WORK}/matte.json" --do specular:${action}
         --screenshot "${WORK}/bad.exr")
  expect("${o}" "${message}" "--do specular:${action}")
endforeach()
message(STATUS "viewer specular pass: all checks passed")
