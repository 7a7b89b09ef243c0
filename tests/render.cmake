# Render tests (label gl): need an X server with OpenGL 4.5 core, e.g.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L gl
kw_add_test(tst_render_layout LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_layout.cpp LIBS knotwork_render)
kw_add_test(tst_render_exact LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_exact.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_baseline LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_baseline.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render PkgConfig::OIIO)
kw_add_test(tst_render_uploads LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_uploads.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_cmd_render LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cmd_render.cpp LIBS PkgConfig::OIIO)
target_compile_definitions(tst_cmd_render PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_cmd_render knotwork knotwork_bench)

# The exact pass picks the per-cell gather or per-fragment fetches per surface from its cells'
# size on screen; run the AOV-vs-kernel test once more with each variant forced, so both stay
# exact whatever the heuristic picks for the scenes above.
foreach(variant IN ITEMS gather:0 fetch:1e30)
  string(REPLACE ":" ";" parts ${variant})
  list(GET parts 0 name)
  list(GET parts 1 threshold)
  add_test(NAME tst_render_exact_${name} COMMAND tst_render_exact)
  set_tests_properties(tst_render_exact_${name} PROPERTIES LABELS gl
    ENVIRONMENT "QT_QPA_PLATFORM=xcb;KW_GATHER_MIN_CELL_PX=${threshold}")
endforeach()
kw_add_test(tst_render_scene LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_scene.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_batch LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_batch.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_incremental LABEL gl SOURCES
            ${CMAKE_CURRENT_LIST_DIR}/tst_render_incremental.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
