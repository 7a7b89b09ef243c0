# render tests (label render); a second label says what a test needs: gl, gui or occt.

# A scene past the GPU's buffer limit (lowered for the test): one short error line with the
# totals, the surfaces that fit drawn (label gl).
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -R tst_render_scale_limit
kw_add_test(tst_render_scale_limit NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_scale_limit.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
