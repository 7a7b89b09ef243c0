# render tests (label render); a second label says what a test needs: gl, gui or occt.

# The polygon pools give back the high-water mark a close-up leaves (GpuPool::compact): the
# close-up and the views after it draw the same bytes as a renderer without that history.
kw_add_test(tst_render_pool_compaction NEEDS gl
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_pool_compaction.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
