# CAD import/export tests (issue 7): trims, OBJ, IGES/STEP/BREP against OpenCASCADE, convert CLI.
set(KW_CAD_TEST_LIBS knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_CAD_TEST_LIBS knotwork_occt)
endif()
kw_add_test(tst_cadimport LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cadimport.cpp LIBS ${KW_CAD_TEST_LIBS})
set_tests_properties(tst_cadimport PROPERTIES TIMEOUT 600)
kw_add_test(tst_trim LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim.cpp LIBS knotwork_model)
kw_add_test(tst_objfile LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_objfile.cpp LIBS knotwork_model)
# knotwork convert as a process (needs the binary); KW_HAVE_OCCT comes with knotwork_cad.
kw_add_test(tst_convert LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_convert.cpp LIBS knotwork_cad)
target_compile_definitions(tst_convert PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_convert knotwork)
set_tests_properties(tst_convert PROPERTIES TIMEOUT 600)
