# Editor GUI tests (label gui): the real main window under Xvfb (QT_QPA_PLATFORM=xcb), e.g.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L gui
kw_add_test(tst_editor LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
kw_add_test(tst_editor_parts LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_parts.cpp
            LIBS knotwork_ui)
