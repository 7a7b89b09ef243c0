# render tests (label render); a second label says what a test needs: gl, gui or occt.

# Section planes: the exact cut on every pixel, caps without holes at 1x and 64x, bad planes, and
# `knotwork render --section` (needs X: run under xvfb-run like the other gl tests).
kw_add_test(tst_render_sections NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_sections.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h ${KW_TEST_SUPPORT_DIR}/knotwork_process.h
            LIBS knotwork_render Qt6::Gui)
target_compile_definitions(tst_render_sections PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_render_sections knotwork)
# The section split's cell classes, without GL: conservative bounds and classes.
kw_add_test(tst_section_cells SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_section_cells.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
