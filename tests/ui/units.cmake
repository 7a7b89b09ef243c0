# ui tests (label ui); a second label says what a test needs: gl, gui or occt.

# Edit › Units… in the editor: convert, relabel, undo, the status bar and Properties (label gui).
kw_add_test(tst_editor_units NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_units.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
