# Trimmed surfaces (issue 4): messy trim input on the CPU (model), the GPU trim mask against the
# CPU classification (gl), and the CAD importer's faces against OCCT's trims (gl).
kw_add_test(tst_trim_messy LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim_messy.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h LIBS knotwork_model)
kw_add_test(tst_render_trims LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trims.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h
            LIBS knotwork_render)
set_tests_properties(tst_render_trims PROPERTIES TIMEOUT 900)
# Issue 7's render check: imported IGES/STEP faces drawn where OCCT's trims put them. Skips
# itself when knotwork_cad was built without OpenCASCADE.
set(KW_CAD_COVERAGE_LIBS knotwork_render knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_CAD_COVERAGE_LIBS knotwork_occt)
endif()
kw_add_test(tst_render_cad_coverage LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_cad_coverage.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h
            LIBS ${KW_CAD_COVERAGE_LIBS})
set_tests_properties(tst_render_cad_coverage PROPERTIES TIMEOUT 900)
kw_use_cad_reader(tst_render_cad_coverage)
# knotwork info on trimmed files (a process; needs no display).
kw_add_test(tst_trim_info LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim_info.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h LIBS knotwork_model)
target_compile_definitions(tst_trim_info PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_trim_info knotwork)
