# CAD import/export tests (issue 7): trims, OBJ, IGES/STEP/BREP against OpenCASCADE, convert CLI.
# importFile reads IGES/STEP/BREP through the knotwork binary (child process); the comparisons
# with OCCT link the in-process reader directly.
set(KW_CAD_TEST_LIBS knotwork_cad)
if(TARGET knotwork_occt_read)
  list(APPEND KW_CAD_TEST_LIBS knotwork_occt_read)
endif()
kw_add_test(tst_cadimport LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cadimport.cpp LIBS ${KW_CAD_TEST_LIBS})
kw_use_cad_reader(tst_cadimport)
set_tests_properties(tst_cadimport PROPERTIES TIMEOUT 600)
kw_add_test(tst_trim LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim.cpp LIBS knotwork_model)
kw_add_test(tst_objfile LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_objfile.cpp LIBS knotwork_model)
# knotwork convert as a process (needs the binary); KW_HAVE_OCCT comes with knotwork_cad.
kw_add_test(tst_convert LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_convert.cpp LIBS knotwork_cad)
target_compile_definitions(tst_convert PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_convert knotwork)
set_tests_properties(tst_convert PROPERTIES TIMEOUT 600)
# Reliability (issue 14): reported hostile inputs, the written-files-reopen property over every
# sample, tests/data file and fuzz corpus, kill -9 during convert, the --mesh cap.
kw_add_test(tst_reliability LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_reliability.cpp
            LIBS knotwork_model)
target_compile_definitions(tst_reliability PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_reliability knotwork)
set_tests_properties(tst_reliability PROPERTIES TIMEOUT 1200)
# Each knotwork process takes about a second on a loaded 2-core machine: allow Qt Test more than
# its default 300 s per function for the property test over every input file.
set_property(TEST tst_reliability APPEND PROPERTY ENVIRONMENT QTEST_FUNCTION_TIMEOUT=1100000)
# The OCCT modules, one per format (docs/IMPORT.md): which module and toolkits each read loads.
if(TARGET knotwork_occt_plugin)
  kw_add_test(tst_cad_modules LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cad_modules.cpp
              ${CMAKE_CURRENT_LIST_DIR}/knotwork_process.h LIBS knotwork_cad)
  target_compile_definitions(tst_cad_modules PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
  kw_use_cad_reader(tst_cad_modules)
endif()
# The CAD child's binary hand-over: round trip, truncation, corruption (model/cad/handover.h).
kw_add_test(tst_handover LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_handover.cpp
            LIBS knotwork_cad)
# The IGES numbering repair's quick check against its full rebuild.
if(TARGET knotwork_occt_read)
  kw_add_test(tst_igesrepair LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_igesrepair.cpp
              LIBS knotwork_occt_read)
endif()
# `render FILE.iges` with the CAD child started by the launcher (model/cad/cadprestart.h).
kw_add_test(tst_cad_prestart LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cad_prestart.cpp
            ${CMAKE_CURRENT_LIST_DIR}/knotwork_process.h LIBS Qt6::Core)
target_compile_definitions(tst_cad_prestart PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_cad_prestart knotwork)
