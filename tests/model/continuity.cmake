# Continuity: the kernel, the CLI report, Match Surface and Keep Seams Closed (model).

# Continuity of shared edges (model/analysis/continuity.h): the kernel on known cases (label model).
kw_add_test(tst_continuity SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_continuity.cpp
            ${KW_TEST_SUPPORT_DIR}/topology_fixtures.h LIBS knotwork_model)
kw_add_test(tst_continuity_import SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_continuity_import.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS ${KW_CONTINUITY_IMPORT_LIBS})
if(TARGET knotwork_occt)
  target_compile_definitions(tst_continuity_import PRIVATE KW_HAVE_OCCT_TOOLKITS)
endif()
target_compile_definitions(tst_continuity_import PRIVATE
                           KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_continuity_import)
# Match Surface on created patches (model/document/matchsurface.h).
kw_add_test(tst_matchsurface SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_matchsurface.cpp
            LIBS knotwork_model)
# Keep Seams Closed in the document and its undo step (model/document/seamkeeper.h, MoveControlPoints).
kw_add_test(tst_seamkeeper SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_seamkeeper.cpp
            ${KW_TEST_SUPPORT_DIR}/topology_fixtures.h LIBS knotwork_edit)
