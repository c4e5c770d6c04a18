# Every control of the viewer once, at a coarse preparation (--epsilon 1e-3 --spp 2): the
# whole of the viewer's code that the panel and the mouse drive, in little time, so that the
# sanitized suite (scripts/run-sanitized-tests.sh) runs it all. The long end-to-end scripts
# (viewer_cli, viewer_daylight, viewer_removal, viewer_specular: the same controls, repeated
# over every bundled edit at the default preparation and compared with the truth) run in the
# plain suite only. Each session here is saved and rendered again by `relight render` at the
# same preparation: the screenshot is render's image within one 8-bit step, as in those scripts.
#  - data/room, per pixel and in the ratio display: a lamp added and moved, a box inserted
#    and dragged, its specular term, a real lamp's slider, the table removed and brought back,
#    the cabinet removed;
#  - data/courtyard, per pixel and in the ratio display: the sun turned by its sliders and by a
#    drag, the sky turned, scaled and a coefficient set, a point lamp added and moved;
#  - data/courtyard in the window itself: the sun turned, made exact in the background;
#  - data/room in the window itself: a virtual lamp's strength and a real object brought back,
#    run in the background as the panel runs them;
#  - a real lamp placed by a click and saved into a copy of the room's scene.json.
# Run as cmake -DVIEWER=... -DRELIGHT=... -DXVFB_RUN=... -DSCENE=data/room
#   -DCOURTYARD=data/courtyard -DWORK=... -P this (and -DVIEWER_PRELOAD=... under the
#   sanitizers: tests/CMakeLists.txt says why).
include(${CMAKE_CURRENT_LIST_DIR}/viewer_common.cmake)
if(NOT DEFINED COURTYARD)
  message(FATAL_ERROR "define COURTYARD")
endif()

# One session: the viewer with the actions in ARGN, saved and rendered again in `display`.
function(session scene name display)
  set(saved "${WORK}/${name}/edit.json")
  file(MAKE_DIRECTORY "${WORK}/${name}")
  viewer(o 0 "${scene}" ${coarse} --display ${display} ${ARGN} --save-edit "${saved}"
         --screenshot "${WORK}/${name}_viewer.png")
  set(render_display --display ${display})
  if(display STREQUAL "ratio")
    list(APPEND render_display --no-pixel-light)
  endif()
  render(o 0 "${scene}" ${coarse} ${render_display} --edit "${saved}" --no-cache
          -o "${WORK}/${name}_render.png")
  same_within_one_step("${WORK}/${name}_viewer.png" "${WORK}/${name}_render.png" "${name}")
endfunction()

set(room_actions --do light:200,20 --do move:V1:150,30 --do box:90,200 --do drag:90,195:150,210
    --do specular:box1:0.3,0.4,0.5:12 --do scale:A:0.4 --do remove:180,155 --do restore:table
    --do remove:118,140)
session("${SCENE}" room_pixel pixel ${room_actions})
session("${SCENE}" room_ratio ratio ${room_actions})
file(READ "${WORK}/room_ratio/edit.json" json)
foreach(key add_lights add_objects specular remove_objects)
  expect("${json}" "\"${key}\"" "room session saved")
endforeach()
expect("${json}" "\"remove_objects\": \\[[^]]*\"cabinet\"" "room session: the cabinet removed")
expect_not("${json}" "\"table\"" "room session: the table brought back")

set(courtyard_actions --do sun:sun:-60,25 --do sundrag:sun:100,120:60,100
    --do rotate:sky:0,0,1:120 --do scale:sky:1.5 --do sh9:sky:2:0.3,0.2,0.1
    --do point:160,200 --do movepoint:P1:120,190)
session("${COURTYARD}" courtyard_pixel pixel ${courtyard_actions})
session("${COURTYARD}" courtyard_ratio ratio ${courtyard_actions})
file(READ "${WORK}/courtyard_ratio/edit.json" json)
foreach(key direction sh9 intensity)
  expect("${json}" "\"${key}\"" "courtyard session saved")
endforeach()

# The window's own loop: the sun turned leaves a quick image, which the window makes exact on
# its worker thread (viewer/background_work.h) while it keeps drawing; its screenshot waits
# for that.
viewer(o 0 "${COURTYARD}" ${coarse} --do sun:sun:-60,25 --window-screenshot "${WORK}/busy.png")
expect("${o}" "making the image exact: done in [0-9.]+ s, in the background"
       "the exact image made in the background")
expect("${o}" "wrote .*busy.png \\([0-9]+x[0-9]+\\)" "window screenshot after the background work")

# The panel's slow actions in the window: a virtual lamp's strength and the table brought
# back run on the worker thread as the panel's slider and "bring back" do (viewer/app.cpp),
# one after another; the screenshot waits for them. The last action names no object: a
# message in the window, which goes on, and exit code 2 (bad input) when it closes.
viewer(o 2 "${SCENE}" ${coarse} --do light:200,20 --do scale:V1:0.5 --do remove:180,155
       --do restore:table --do restore:nosuch --window-screenshot "${WORK}/panel.png")
foreach(action scale:V1:0.5 restore:table)
  expect("${o}" "--do ${action}: done in [0-9.]+ s, in the background"
         "the panel's action ${action} made in the background")
endforeach()
expect("${o}" "--do restore:nosuch failed: [^\n]*nosuch" "a failed scripted action named")
expect("${o}" "wrote .*panel.png \\([0-9]+x[0-9]+\\)"
       "window screenshot after the panel's actions")

copy_room("${WORK}/lamps")
viewer(o 0 "${WORK}/lamps" ${coarse} --display ratio --do lamp:160,20:0.3,0.2 --save-lamps
       --screenshot "${WORK}/lamps.png")
expect("${o}" "added 1 lamp[s]? to [^\n]*lamps/scene.json" "lamp saved")
render(o 0 "${WORK}/lamps" ${coarse} --no-cache -o "${WORK}/lamps_render.png")
message(STATUS "viewer smoke: all controls ran")
