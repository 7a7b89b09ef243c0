# Faces shaded from their analytic form in closed form (label gl: OpenGL 4.5, Xvfb).
kw_add_test(tst_render_analytic NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_analytic.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h ${KW_TEST_SUPPORT_DIR}/trim_test_util.h
            LIBS knotwork_render)
# Their batches, routes and re-planning (no GL).
kw_add_test(tst_render_analytic_plan SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_analytic_plan.cpp
            LIBS knotwork_render)
