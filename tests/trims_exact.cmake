# Exact trim edges (issue 11): monotone arcs and the hybrid trim grid on the CPU (model).
set(KW_TRIM_EXACT_LIBS knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_TRIM_EXACT_LIBS knotwork_occt)
endif()
kw_add_test(tst_trim_exact LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim_exact.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h LIBS ${KW_TRIM_EXACT_LIBS})
set_tests_properties(tst_trim_exact PROPERTIES TIMEOUT 600)
# It imports hammer.iges, which is read by the knotwork binary in a child process.
kw_use_cad_reader(tst_trim_exact)
# The exact trim mode on the GPU against the CPU classification (gl).
set(KW_TRIM_EXACT_GL_LIBS knotwork_render knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_TRIM_EXACT_GL_LIBS knotwork_occt)
endif()
kw_add_test(tst_render_trims_exact LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trims_exact.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h
            LIBS ${KW_TRIM_EXACT_GL_LIBS})
set_tests_properties(tst_render_trims_exact PROPERTIES TIMEOUT 900)
kw_use_cad_reader(tst_render_trims_exact)
# Anti-aliased trim edges and silhouettes (issue 11 item 4, gl).
kw_add_test(tst_render_trims_aa LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trims_aa.cpp
            ${CMAKE_CURRENT_LIST_DIR}/trim_test_util.h ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h
            LIBS knotwork_render)
