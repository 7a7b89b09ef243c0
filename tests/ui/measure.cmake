# ui tests (label ui); a second label says what a test needs: gl, gui or occt.

# The Measure menu in the editor: probe, measure distance, angle and radius, and the Properties
# panel's measured values (label gui, Xvfb).
kw_add_test(tst_measure_gui NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_measure_gui.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
