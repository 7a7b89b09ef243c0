# Exact trim edges (issue 11): monotone arcs and the hybrid trim grid on the CPU (model).
set(KW_TRIM_EXACT_LIBS knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_TRIM_EXACT_LIBS knotwork_occt)
endif()
kw_add_test(tst_trim_exact LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim_exact.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h LIBS ${KW_TRIM_EXACT_LIBS})
set_tests_properties(tst_trim_exact PROPERTIES TIMEOUT 600)
