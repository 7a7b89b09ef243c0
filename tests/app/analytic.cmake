# Analytic faces in closed form through the CAD child and `knotwork info --json` (needs the
# knotwork binary and OpenCASCADE).
if(TARGET knotwork_occt_read)
  kw_add_test(tst_analytic_info NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analytic_info.cpp
              ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS knotwork_occt_read)
  target_compile_definitions(tst_analytic_info PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
  kw_use_cad_reader(tst_analytic_info)
endif()
