# The editor's first minutes: the first window's layout and toolbars, the saved layout at the
# next start, Fit and markers with hidden surfaces, where new shapes appear.
kw_add_test(tst_editor_first_minutes LABEL gui
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_first_minutes.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
