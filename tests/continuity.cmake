# Continuity of shared edges (model/continuity.h): the kernel on known cases (label model).
kw_add_test(tst_continuity LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_continuity.cpp
            ${KW_TEST_SUPPORT_DIR}/topology_fixtures.h LIBS knotwork_model)
# The closed solids of tests/data, imported through the CAD child, against OpenCASCADE's own
# count of edges between two faces (where OCCT is built), and `knotwork info --continuity`.
set(KW_CONTINUITY_IMPORT_LIBS knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_CONTINUITY_IMPORT_LIBS knotwork_occt)
endif()
kw_add_test(tst_continuity_import LABEL model
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_continuity_import.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS ${KW_CONTINUITY_IMPORT_LIBS})
if(TARGET knotwork_occt)
  target_compile_definitions(tst_continuity_import PRIVATE KW_HAVE_OCCT_TOOLKITS)
endif()
target_compile_definitions(tst_continuity_import PRIVATE
                           KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_continuity_import)
# Match Surface on created patches (model/matchsurface.h).
kw_add_test(tst_matchsurface LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_matchsurface.cpp
            LIBS knotwork_model)
# Keep Seams Closed in the document and its undo step (model/seamkeeper.h, MoveControlPoints).
kw_add_test(tst_seamkeeper LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_seamkeeper.cpp
            ${KW_TEST_SUPPORT_DIR}/topology_fixtures.h LIBS knotwork_edit)
# The Edge Continuity overlay's bands on the GPU against the kernel's classes (gl).
kw_add_test(tst_render_edge_bands LABEL gl
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_edge_bands.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
# The editor's overlay, tolerances and Keep Seams Closed (gui).
kw_add_test(tst_editor_continuity LABEL gui
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_continuity.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
