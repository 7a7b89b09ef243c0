# ui tests (label ui); a second label says what a test needs: gl, gui or occt.

# The editor's View › Section…: add, move, flip, no undo step, saved with the project.
kw_add_test(tst_editor_sections NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_sections.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
