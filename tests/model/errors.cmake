# Which file a failed CAD-to-CAD conversion names: the read's IN, the write's OUT.
kw_add_test(tst_convert_errors NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_convert_errors.cpp
            LIBS ${KW_CAD_TEST_LIBS})
kw_use_cad_reader(tst_convert_errors)
