# render tests (label render); a second label says what a test needs: gl, gui or occt.

# Base polygons keep only the cells that may reach the view: every cell on screen is kept, and
# close-ups are the same bytes as with every cell (RenderOptions::polygonsInView).
kw_add_test(tst_render_in_view NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_in_view.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
