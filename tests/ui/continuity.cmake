# ui tests (label ui); a second label says what a test needs: gl, gui or occt.

# The editor's overlay, tolerances and Keep Seams Closed (gui).
kw_add_test(tst_editor_continuity NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_continuity.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
