# ui tests (label ui); a second label says what a test needs: gl, gui or occt.

# Gestures as tools: the live-edit protocol without widgets, and the 3D view's tool routing.
kw_add_test(tst_live_edit SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_live_edit.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h LIBS knotwork_edit)
kw_add_test(tst_tools NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_tools.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
