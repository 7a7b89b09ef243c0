# render tests (label render); a second label says what a test needs: gl, gui or occt.

# The partial frame after edits of real models: the same pixels and pre-pass data as the whole
# frame, whole where it must be (gl; imports hammer.iges and Motor-c.brep through the CAD reader).
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -R tst_render_partial_frame
kw_add_test(tst_render_partial_frame NEEDS gl SOURCES
            ${CMAKE_CURRENT_LIST_DIR}/tst_render_partial_frame.cpp
            ${KW_TEST_SUPPORT_DIR}/cad_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS ${KW_PINHOLE_LIBS})
kw_use_cad_reader(tst_render_partial_frame)
# Its bookkeeping without GL: the rectangle after changed, hidden and shown surfaces and edge
# bands, the cases drawn whole, the kept camera planes (label render).
kw_add_test(tst_partial_frame_damage SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_partial_frame_damage.cpp
            LIBS knotwork_render)
# The cells a partial frame's rectangle reaches, their runs and the planner's commands for them,
# without GL (label render).
kw_add_test(tst_partial_cells SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_partial_cells.cpp
            LIBS knotwork_render)
# The damage tiles a partial frame narrows its rectangle to: the tiles of rectangles and of a
# polygon's cells, and the rectangles covering them, without GL (label render).
kw_add_test(tst_damage_tiles SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_damage_tiles.cpp
            LIBS knotwork_render)
