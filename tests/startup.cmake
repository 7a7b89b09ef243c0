# Start-up and first image (issue 15 item 6): the trim grid cap `knotwork render` sets from the
# image size changes no pixel. `render FILE.step` itself is tested in tst_cmd_render.
kw_add_test(tst_render_trim_grid_cap LABEL gl
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trim_grid_cap.cpp
                    ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h
            LIBS knotwork_render)
