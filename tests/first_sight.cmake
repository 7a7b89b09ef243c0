# What a new user sees first: zebra stripes against their definition, every visible face lit,
# and the automatic colour range of the curvature maps (label gl: OpenGL 4.5).
kw_add_test(tst_render_zebra LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_zebra.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
# The default rig lights every visible face: samples and tests/data's CAD parts (imported
# through the CAD reader) from the standard views and random ones.
set(KW_LIGHTING_LIBS knotwork_render knotwork_cad)
if(TARGET knotwork_occt)
  list(APPEND KW_LIGHTING_LIBS knotwork_occt)
endif()
kw_add_test(tst_render_lighting LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_lighting.cpp
            ${CMAKE_CURRENT_LIST_DIR}/cad_test_util.h ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h
            LIBS ${KW_LIGHTING_LIBS})
kw_use_cad_reader(tst_render_lighting)
# The automatic colour range: area-weighted percentiles (no GL).
kw_add_test(tst_analysis_range LABEL render SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analysis_range.cpp
            LIBS knotwork_render)
# The background saved with the project (no GL).
kw_add_test(tst_background_setting LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_background_setting.cpp
            LIBS knotwork_render)
# View › Light Background in the editor, saved with the project (label gui).
kw_add_test(tst_editor_background LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_background.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
