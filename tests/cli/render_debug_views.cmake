# End to end through the `relight` binary: render --debug-views writes the views and an
# index, gives the same relit image as a render from the cache, leaves a valid cache, and
# fails at once, naming it, when the folder cannot be made. Run by ctest
# (tests/CMakeLists.txt):
#   cmake -DRELIGHT=<relight binary> -DSCENE=<data/room> -DWORK=<scratch folder> -P this
include("${CMAKE_CURRENT_LIST_DIR}/common.cmake")

file(REMOVE_RECURSE "${WORK}")
set(room "${WORK}/room")
copy_room("${room}")
set(edit "${SCENE}/edits/back_off.json")
set(views "${WORK}/views")
# Cheap settings: the test checks the plumbing, not the picture.
set(cheap --epsilon 1e-3 --spp 4)

# The reference: prepared once, rendered from the cache.
relight(out 0 prepare "${room}" ${cheap})
relight(out 0 render "${room}" ${cheap} --edit "${edit}" -o "${WORK}/cached.exr")
expect("${out}" "using cache" "render from the cache")

# With --debug-views: prepared in memory (the cache lacks the solver state), views written.
relight(out 0 render "${room}" ${cheap} --edit "${edit}" -o "${WORK}/views.exr"
        --debug-views "${views}" --report "${WORK}/report.json")
expect("${out}" "solver state is needed[^\n]*; preparing" "render --debug-views")
expect("${out}" "wrote debug views [^\n]*views \\(12 files" "render --debug-views")
foreach(f B.exr B.png D.exr D.png T_orig.png T_inter.png T_final.png reflectance.png H_photo.exr
          mesh.png frontier.png index.json)
  if(NOT EXISTS "${views}/${f}")
    message(FATAL_ERROR "render --debug-views wrote no ${f}")
  endif()
endforeach()
file(READ "${WORK}/report.json" json)
string(JSON dv GET "${json}" debug_views)
expect("${dv}" "views$" "report's debug_views")
string(JSON t GET "${json}" time_s debug_views)
expect("${t}" "^[0-9.e+-]+$" "report's time_s.debug_views")

# The relit image is the same as without debug views (preparation is deterministic), bit
# for bit. OpenImageIO stamps each EXR with the time it was written: the header attribute
# capDate (name, type "string", length 19, "YYYY:MM:DD HH:MM:SS") is cut out first.
function(exr_hash file out)
  file(READ "${file}" hex HEX)
  # "capDate\0" "string\0" then the length 19 as int32, little-endian.
  set(attr "6361704461746500737472696e670013000000")
  string(FIND "${hex}" "${attr}" at)
  if(at GREATER_EQUAL 0)
    string(LENGTH "${attr}" n)
    math(EXPR valueAt "${at} + ${n}")
    math(EXPR afterValue "${valueAt} + 38")  # 19 bytes
    string(SUBSTRING "${hex}" 0 ${valueAt} head)
    string(SUBSTRING "${hex}" ${afterValue} -1 tail)
    set(hex "${head}${tail}")
  endif()
  string(SHA256 h "${hex}")
  set(${out} "${h}" PARENT_SCOPE)
endfunction()
exr_hash("${WORK}/cached.exr" a)
exr_hash("${WORK}/views.exr" b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "render --debug-views gave another image than the render from the cache")
endif()

# The cache it wrote is valid: the next render uses it.
relight(out 0 render "${room}" ${cheap} -o "${WORK}/after.png")
expect("${out}" "using cache" "render after render --debug-views")

# Without a cache, with views: works too.
relight(out 0 render "${room}" ${cheap} --no-cache -o "${WORK}/nocache.png"
        --debug-views "${WORK}/views2")
expect("${out}" "wrote debug views" "--no-cache --debug-views")

# An edit that inserts a box: the leaves under its shadow are split (Loscos et al. 2000,
# Fig. 24(a)), and mesh_edit.png shows them; an edit that inserts nothing skips that view.
relight(out 0 render "${room}" ${cheap} --edit "${SCENE}/edits/virtual_box.json"
        -o "${WORK}/box.exr" --debug-views "${WORK}/views3")
expect("${out}" "inserted object [^\n]*, [1-9][0-9]* leaves split under its shadows"
       "render virtual_box")
expect("${out}" "wrote debug views [^\n]*views3 \\(13 files" "render virtual_box --debug-views")
if(NOT EXISTS "${WORK}/views3/mesh_edit.png")
  message(FATAL_ERROR "render --debug-views of an edit with a box wrote no mesh_edit.png")
endif()
file(READ "${views}/index.json" index)
expect("${index}" "mesh_edit.png[^}]*the edit inserts nothing" "index.json of back_off")

# A folder that cannot be made: fails at once, before any preparation, naming it.
file(WRITE "${WORK}/blocker" "a file where a folder should be")
relight(out 3 render "${room}" ${cheap} -o "${WORK}/x.png" --debug-views "${WORK}/blocker/views")
expect("${out}" "error: [^\n]*blocker/views: cannot create the debug-views folder" "bad folder")
expect_not("${out}" "preparing|using cache" "bad folder")

file(REMOVE_RECURSE "${WORK}")
