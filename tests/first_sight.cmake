# What a new user sees first: zebra stripes against their definition, every visible face lit,
# and the automatic colour range of the curvature maps (label gl: OpenGL 4.5).
kw_add_test(tst_render_zebra LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_zebra.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
