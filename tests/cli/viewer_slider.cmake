# A lamp's slider moved with a box in the room (issue 32), in the per-pixel display (the
# viewer's default): while it moves, the session's quick image (Session::update, the box's
# links kept); the slider at rest, the box inserted again at the new radiance
# (Session::settle, its shadow rays from the session's GeometryCache): the screenshot is
# what `relight render` draws of the saved edit, within one 8-bit step (as viewer_cli.cmake).
# Both at the coarse preparation (viewer_common.cmake's ${coarse}).
# Run as cmake -DVIEWER=... -DRELIGHT=... -DXVFB_RUN=... -DSCENE=data/room -DWORK=... -P this
include(${CMAKE_CURRENT_LIST_DIR}/viewer_common.cmake)
file(MAKE_DIRECTORY "${WORK}")
viewer(o 0 "${SCENE}" ${coarse} --edit "${SCENE}/edits/virtual_box.json" --do scale:A:0.4
       --do scale:A:2 --save-edit "${WORK}/slider.json" --screenshot "${WORK}/slider_viewer.png")
file(READ "${WORK}/slider.json" json)
expect("${json}" "\"add_objects\"" "saved slider session")
render(o 0 "${SCENE}" ${coarse} --edit "${WORK}/slider.json" -o "${WORK}/slider_render.png")
same_within_one_step("${WORK}/slider_viewer.png" "${WORK}/slider_render.png"
                     "per-pixel display, a lamp's slider with a box")
