# render tests (label render); a second label says what a test needs: gl, gui or occt.

kw_add_test(tst_render_pinholes NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_pinholes.cpp
            ${KW_TEST_SUPPORT_DIR}/cad_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS ${KW_PINHOLE_LIBS})
kw_use_cad_reader(tst_render_pinholes)
