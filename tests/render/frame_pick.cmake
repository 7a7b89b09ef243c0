# render tests (label render); a second label says what a test needs: gl, gui or occt.

# The frame on screen answers a pick on the forward pass's pixels as on the deferred pass's
# (Renderer::pickInLastFrame; the probe's hover reads it).
kw_add_test(tst_render_frame_pick NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_frame_pick.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
