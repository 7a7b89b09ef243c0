# model tests (label model); a second label says what a test needs: gl, gui or occt.

# The document's length unit: .knot, the CAD hand-over, the Units command (no GUI).
kw_add_test(tst_units SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_units.cpp
            LIBS knotwork_edit knotwork_cad)
