# render tests (label render); a second label says what a test needs: gl, gui or occt.

# The Edge Continuity overlay's bands on the GPU against the kernel's classes (gl).
kw_add_test(tst_render_edge_bands NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_edge_bands.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
