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
add_dependencies(tst_cmd_render knotwork)
