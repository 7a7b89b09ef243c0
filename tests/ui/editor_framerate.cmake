# ui tests (label ui); a second label says what a test needs: gl, gui or occt.

# The editor's frames while the view moves (previews) and at rest (the full image, the same
# bytes), the probe read from the frame, and a printed per-pass profile of orbit and drag
# (label gui, Xvfb; imports hammer.iges and teapot.igs through the CAD reader).
kw_add_test(tst_editor_framerate NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_framerate.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h ${KW_TEST_SUPPORT_DIR}/cad_test_util.h
            LIBS knotwork_ui knotwork_cad)
kw_use_cad_reader(tst_editor_framerate)
