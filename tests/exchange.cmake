# CAD export (docs/EXCHANGE.md): round trips through STEP and IGES, closed solids, open seams,
# bad destinations; the exported files checked in process with OpenCASCADE.
if(TARGET knotwork_occt_write)
  kw_add_test(tst_exchange LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_exchange.cpp
              ${CMAKE_CURRENT_LIST_DIR}/knotwork_process.h LIBS knotwork_occt_write)
  target_compile_definitions(tst_exchange PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
  kw_use_cad_reader(tst_exchange)
  set_tests_properties(tst_exchange PROPERTIES TIMEOUT 900)
endif()
# The editor's File ▸ Export… and Save As with a CAD name (label gui, Xvfb).
kw_add_test(tst_editor_export LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_export.cpp
            LIBS knotwork_ui)
kw_use_cad_reader(tst_editor_export)
target_compile_definitions(tst_editor_export PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
# The AOV of a part read back from STEP against the original's (label gl, Xvfb).
if(TARGET knotwork_occt_write)
  kw_add_test(tst_render_exchange LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_exchange.cpp
              ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render knotwork_cad)
  kw_use_cad_reader(tst_render_exchange)
endif()
