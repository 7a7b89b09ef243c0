# Autosave, crash recovery and .bak copies in the editor (label gui: the real main window).
kw_add_test(tst_recovery LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_recovery.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
