# model tests (label model); a second label says what a test needs: gl, gui or occt.

# Section planes in the project file and validation (no GL).
kw_add_test(tst_section_file SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_section_file.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h LIBS knotwork_model)
