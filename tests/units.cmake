# The document's length unit: .knot, the CAD hand-over, the Units command (no GUI).
kw_add_test(tst_units LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_units.cpp
            LIBS knotwork_edit knotwork_cad)
# Edit › Units… in the editor: convert, relabel, undo, the status bar and Properties (label gui).
kw_add_test(tst_editor_units LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_units.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
