# render tests (label render); a second label says what a test needs: gl, gui or occt.

# The base polygon's bound near the eye: the depth of what is in view where control bounds
# reach past the near plane (kw::boxMinDepthInFrustum), so close-ups meet the tolerance.
kw_add_test(tst_near_eye_bound SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_near_eye_bound.cpp
            LIBS knotwork_render)

# Exact trim grids are held only for the trimmed surfaces in view (TrimMaskPass::syncExact).
kw_add_test(tst_render_trims_in_view NEEDS gl SOURCES
            ${CMAKE_CURRENT_LIST_DIR}/tst_render_trims_in_view.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
