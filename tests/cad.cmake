# CAD import/export tests (issue 7): trims, OBJ, IGES/STEP/BREP against OpenCASCADE, convert CLI.
set(KW_CAD_TEST_LIBS knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_CAD_TEST_LIBS knotwork_occt)
endif()
kw_add_test(tst_cadimport LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cadimport.cpp LIBS ${KW_CAD_TEST_LIBS})
set_tests_properties(tst_cadimport PROPERTIES TIMEOUT 600)
kw_add_test(tst_trim LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim.cpp LIBS knotwork_model)
kw_add_test(tst_objfile LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_objfile.cpp LIBS knotwork_model)
