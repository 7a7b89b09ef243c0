# A reduced pinhole sweep over random views of tests/data's closed solids against the CPU
# reference (label gl; tools/pinhole_sweep.py runs the full sweep).
set(KW_PINHOLE_LIBS knotwork_render knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_PINHOLE_LIBS knotwork_occt)
endif()
kw_add_test(tst_render_pinholes LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_pinholes.cpp
            ${KW_TEST_SUPPORT_DIR}/cad_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS ${KW_PINHOLE_LIBS})
kw_use_cad_reader(tst_render_pinholes)
